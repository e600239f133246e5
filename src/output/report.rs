//! A picture of the result: the paper's 1-D symmetry space (each symmetry a point at its
//! complexity on a line, coloured by group) above a heatmap of each functional map `C`
//! (blue negative, red positive, white zero). SVG, or SVG inside a small HTML page with a table.

use std::fmt::Write;

use super::PALETTE;
use crate::detect::Detection;

fn rgb(c: [u8; 3]) -> String {
    format!("rgb({},{},{})", c[0], c[1], c[2])
}

/// The report as an SVG document.
pub fn svg(det: &Detection, title: &str) -> String {
    let n = det.symmetries.len();
    let cols = 4usize;
    let cell = 150.0;
    let rows = n.div_ceil(cols).max(1);
    let width = 40.0 + cols as f64 * (cell + 30.0);
    let height = 185.0 + rows as f64 * (cell + 60.0);
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
    s.push_str("</svg>\n");
    s
}

/// The report as an HTML page: the SVG and a table of the symmetries.
pub fn html(det: &Detection, title: &str) -> String {
    let mut s = format!("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>{0}</title></head><body><h1>{0}</h1>\n", escape(title));
    s.push_str(&svg(det, title));
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
