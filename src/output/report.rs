//! A picture of the result: the paper's 1-D symmetry space (each symmetry a point at its
//! complexity on a line, coloured by group) above a heatmap of each functional map `C`
//! (blue negative, red positive, white zero), and, given the vertices, where each partial
//! symmetry goes: its region (orange) and its image (blue) on a projection of the shape (onto
//! its two widest coordinate axes). SVG, or SVG inside a small HTML page with a table.

use std::fmt::Write;

use super::PALETTE;
use crate::detect::Detection;
use crate::mesh::vec3::dist2;

fn rgb(c: [u8; 3]) -> String {
    format!("rgb({},{},{})", c[0], c[1], c[2])
}

/// The report as an SVG document; with the mesh's `vertices` (input indices), one more panel
/// per partial symmetry showing which part maps to which.
pub fn svg(det: &Detection, title: &str, vertices: Option<&[[f64; 3]]>) -> String {
    let n = det.symmetries.len();
    let cols = 4usize;
    let cell = 150.0;
    let rows = n.div_ceil(cols).max(1);
    let partial: Vec<usize> = match vertices {
        Some(v) if v.len() == det.vertices => (0..n).filter(|&i| det.symmetries[i].kind == crate::detect::Kind::Partial).collect(),
        _ => Vec::new(),
    };
    let region_rows = partial.len().div_ceil(cols);
    let width = 40.0 + cols as f64 * (cell + 30.0);
    let height = 185.0 + (rows + region_rows) as f64 * (cell + 60.0);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = write!(s, r#"<rect width="100%" height="100%" fill="white"/><text x="20" y="24" font-size="16">{}</text>"#, escape(title));
    // Symmetry space.
    let max_c = det.symmetries.iter().map(|s| s.complexity).fold(1e-9, f64::max) * 1.1;
    let (x0, x1, y) = (40.0, width - 40.0, 90.0);
    let _ = write!(s, r#"<line x1="{x0}" y1="{y}" x2="{x1}" y2="{y}" stroke="black"/>"#);
    let _ = write!(s, r#"<text x="{x0}" y="{}">0</text><text x="{}" y="{}" text-anchor="end">complexity {max_c:.2}</text>"#, y + 20.0, x1, y + 20.0);
    let _ = write!(s, r#"<text x="{x0}" y="50">symmetry space (⟨W,|C|⟩/‖C‖): isometric at 0, more complex to the right</text>"#);
    for (i, sym) in det.symmetries.iter().enumerate() {
        let x = x0 + (x1 - x0) * sym.complexity / max_c;
        let c = PALETTE[sym.group % PALETTE.len()];
        let dy = if i % 2 == 0 { -14.0 } else { 26.0 };
        let _ = write!(s, r#"<circle cx="{x:.1}" cy="{y}" r="6" fill="{}" stroke="black"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">#{i}</text>"#, rgb(c), y + dy);
    }
    // Heatmaps.
    for (i, sym) in det.symmetries.iter().enumerate() {
        let (r, c) = (i / cols, i % cols);
        let ox = 20.0 + c as f64 * (cell + 30.0);
        let oy = 165.0 + r as f64 * (cell + 60.0);
        let k = sym.fmap.nrows().max(1);
        let px = cell / k as f64;
        let amax = (0..sym.fmap.nrows()).flat_map(|a| (0..k).map(move |b| (a, b))).map(|(a, b)| sym.fmap[(a, b)].abs()).fold(1e-12, f64::max);
        let _ = write!(
            s,
            r#"<text x="{ox}" y="{:.1}">#{i} {} · group {}</text><text x="{ox}" y="{:.1}">order {} · complexity {:.2}</text>"#,
            oy - 20.0,
            sym.kind.as_str(),
            sym.group,
            oy - 6.0,
            sym.order,
            sym.complexity
        );
        for a in 0..sym.fmap.nrows() {
            for b in 0..sym.fmap.ncols() {
                let v = sym.fmap[(a, b)] / amax;
                let fill = if v >= 0.0 {
                    rgb([255, (255.0 * (1.0 - v)) as u8, (255.0 * (1.0 - v)) as u8])
                } else {
                    rgb([(255.0 * (1.0 + v)) as u8, (255.0 * (1.0 + v)) as u8, 255])
                };
                let _ = write!(s, r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{fill}"/>"#, ox + b as f64 * px, oy + a as f64 * px, px + 0.05, px + 0.05);
            }
        }
        let _ = write!(s, r#"<rect x="{ox}" y="{oy}" width="{cell}" height="{cell}" fill="none" stroke="black"/>"#);
    }
    if n == 0 {
        let _ = write!(s, r#"<text x="40" y="170">no symmetry found</text>"#);
    }
    if let Some(vertices) = vertices.filter(|_| !partial.is_empty()) {
        let top = 165.0 + rows as f64 * (cell + 60.0);
        regions(&mut s, det, &partial, vertices, top, cols, cell);
    }
    s.push_str("</svg>\n");
    s
}

/// Panels of the partial symmetries `which`: the vertices (every k-th, about 4,000 drawn) on the
/// projection onto the two widest coordinate axes, grey; the region's source side orange,
/// its image blue (an involution on both sides: a vertex is on the source side when it is
/// nearer the source seed than its image is).
fn regions(s: &mut String, det: &Detection, which: &[usize], vertices: &[[f64; 3]], top: f64, cols: usize, cell: f64) {
    let (lo, hi) = vertices.iter().fold(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |(lo, hi), p| (std::array::from_fn(|d| lo[d].min(p[d])), std::array::from_fn(|d| hi[d].max(p[d]))));
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| (hi[b] - lo[b]).total_cmp(&(hi[a] - lo[a])));
    let (u, v) = (axes[0], axes[1]);
    let span = (hi[u] - lo[u]).max(hi[v] - lo[v]).max(1e-12);
    let at = |p: &[f64; 3]| ((p[u] - lo[u]) / span * (cell - 10.0) + 5.0, (hi[v] - p[v]) / span * (cell - 10.0) + 5.0);
    let stride = vertices.len().div_ceil(4000).max(1);
    for (slot, &i) in which.iter().enumerate() {
        let sym = &det.symmetries[i];
        let (ox, oy) = (20.0 + (slot % cols) as f64 * (cell + 30.0), top + (slot / cols) as f64 * (cell + 60.0));
        let _ = write!(s, r#"<text x="{ox}" y="{:.1}">#{i} partial: {} vertices</text><text x="{ox}" y="{:.1}" fill="rgb(230,120,0)">region</text><text x="{:.1}" y="{:.1}" fill="rgb(30,90,220)">→ image</text>"#, oy - 20.0, sym.region_size, oy - 6.0, ox + 50.0, oy - 6.0);
        let (src, dst) = (&vertices[sym.source.min(vertices.len() - 1)], &vertices[sym.target.min(vertices.len() - 1)]);
        for (w, p) in vertices.iter().enumerate() {
            if w % stride != 0 {
                continue;
            }
            let m = sym.map[w];
            let colour = if m < 0 || m as usize >= vertices.len() {
                "rgb(200,200,200)"
            } else if dist2(*p, *src) - dist2(*p, *dst) <= dist2(vertices[m as usize], *src) - dist2(vertices[m as usize], *dst) {
                "rgb(230,120,0)"
            } else {
                "rgb(30,90,220)"
            };
            let (x, y) = at(p);
            let _ = write!(s, r#"<circle cx="{:.1}" cy="{:.1}" r="0.9" fill="{colour}"/>"#, ox + x, oy + y);
        }
        let _ = write!(s, r#"<rect x="{ox}" y="{oy}" width="{cell}" height="{cell}" fill="none" stroke="black"/>"#);
    }
}

/// The report as an HTML page: the SVG and a table of the symmetries.
pub fn html(det: &Detection, title: &str, vertices: Option<&[[f64; 3]]>) -> String {
    let mut s = format!("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>{0}</title></head><body><h1>{0}</h1>\n", escape(title));
    s.push_str(&svg(det, title, vertices));
    s.push_str("<table border=\"1\" cellpadding=\"4\"><tr><th>#</th><th>kind</th><th>group</th><th>order</th><th>complexity</th><th>distortion</th><th>region</th><th>seed</th></tr>\n");
    for (i, sym) in det.symmetries.iter().enumerate() {
        let _ = writeln!(
            s,
            "<tr><td>{i}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.3}</td><td>{:.4}</td><td>{} / {}</td><td>{} → {}</td></tr>",
            sym.kind.as_str(),
            sym.group,
            sym.order,
            sym.complexity,
            sym.distortion,
            sym.region_size,
            det.vertices,
            sym.source,
            sym.target
        );
    }
    s.push_str("</table></body></html>\n");
    s
}

fn escape(t: &str) -> String {
    t.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
