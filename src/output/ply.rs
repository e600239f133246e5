//! Coloured PLY output (binary little endian): per-vertex colour and a
//! float `quality` property, which MeshLab reads as vertex quality.
//!
//! Colouring ([`correspondence_colours`]): a vertex and its image under the chosen symmetry get
//! the same colour — a symmetric function of `p(v)` and `p(T v)`: per channel, their mean and
//! the mean of their squares, in bounding-box coordinates mapped to [−1, 1] — so mirrored
//! parts are painted alike; vertices outside the region are grey. The squares matter where the
//! mean says nothing: a sphere's antipodal map sends every midpoint to the centre, and the
//! midpoint alone painted the whole sphere one colour (issue 16, item 21).

use std::path::Path;

use crate::mesh::{IoError, RawMesh};

/// Grey for vertices outside a symmetry's region.
pub const OUTSIDE: [u8; 3] = [150, 150, 150];

/// `(n,)` colours in which `v` and `map[v]` agree (for an involution exactly).
pub fn correspondence_colours(vertices: &[[f64; 3]], map: &[i64]) -> Vec<[u8; 3]> {
    let (lo, hi) = crate::mesh::bounding_box(vertices);
    // Bounding-box coordinates in [−1, 1].
    let unit = |p: &[f64; 3], d: usize| if hi[d] > lo[d] { (2.0 * p[d] - lo[d] - hi[d]) / (hi[d] - lo[d]) } else { 0.0 };
    vertices
        .iter()
        .zip(map)
        .map(|(p, &t)| {
            let Some(q) = usize::try_from(t).ok().and_then(|t| vertices.get(t)) else {
                return OUTSIDE;
            };
            std::array::from_fn(|d| {
                let (u, v) = (unit(p, d), unit(q, d));
                let x = 0.5 + 0.15 * (u + v) + 0.45 * (0.5 * (u * u + v * v) - 0.33);
                (40.0 + 200.0 * x.clamp(0.0, 1.0)) as u8
            })
        })
        .collect()
}

/// Writes `mesh` with `colours` `(n,)` and `quality` `(n,)` as binary PLY.
///
/// The records are written straight to the file. `ply-rs-bw` (which reads PLY input, in
/// `crate::mesh::io`) would first build one element per record, a hash map of named
/// properties each: on a 955k-vertex mesh that took 4 s and 1.3 GiB more than the whole
/// detection (issue 17); the format of this one layout is a dozen lines.
pub fn write_ply(path: impl AsRef<Path>, mesh: &RawMesh, colours: &[[u8; 3]], quality: &[f64]) -> Result<(), IoError> {
    use std::io::Write;
    let path = path.as_ref();
    let os = |source| IoError::Os { path: path.into(), source };
    let file = std::fs::File::create(path).map_err(os)?;
    let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by intrinsym: colour = symmetry correspondence, quality = symmetry confidence\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
         property float quality\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    w.write_all(header.as_bytes()).map_err(os)?;
    for (i, p) in mesh.vertices.iter().enumerate() {
        // x y z (float), red green blue (uchar), quality (float): 19 bytes.
        let mut record = [0u8; 19];
        for (d, x) in p.iter().enumerate() {
            record[4 * d..4 * d + 4].copy_from_slice(&(*x as f32).to_le_bytes());
        }
        record[12..15].copy_from_slice(&colours.get(i).copied().unwrap_or(OUTSIDE));
        record[15..19].copy_from_slice(&(quality.get(i).copied().unwrap_or(0.0) as f32).to_le_bytes());
        w.write_all(&record).map_err(os)?;
    }
    for t in &mesh.triangles {
        // The count (uchar 3), then three int indices: 13 bytes.
        let mut record = [3u8; 13];
        for (k, &i) in t.iter().enumerate() {
            record[1 + 4 * k..5 + 4 * k].copy_from_slice(&(i as i32).to_le_bytes());
        }
        w.write_all(&record).map_err(os)?;
    }
    w.flush().map_err(os)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::read_mesh;

    /// A sphere's antipodal map paints the sphere in many colours, not one (issue 16, item 21),
    /// and a vertex and its image share theirs.
    #[test]
    fn the_antipodal_map_of_a_sphere_is_not_one_colour() {
        let sphere = crate::shapes::icosphere(3);
        let key = |p: [f64; 3]| p.map(|x| (x * 1e6).round() as i64);
        let index: std::collections::HashMap<[i64; 3], i64> = sphere.vertices.iter().enumerate().map(|(i, &p)| (key(p), i as i64)).collect();
        let antipodal: Vec<i64> = sphere.vertices.iter().map(|p| index[&key(p.map(|x| -x))]).collect();
        let colours = correspondence_colours(&sphere.vertices, &antipodal);
        let distinct: std::collections::HashSet<[u8; 3]> = colours.iter().copied().collect();
        assert!(distinct.len() >= 50, "{} colours", distinct.len());
        assert!(antipodal.iter().enumerate().all(|(v, &t)| colours[v] == colours[t as usize]));
        // A map index outside the mesh is "outside", not a crash.
        assert_eq!(correspondence_colours(&sphere.vertices[..2], &[5, -1]), vec![OUTSIDE, OUTSIDE]);
    }

    #[test]
    fn ply_round_trips_and_mirror_vertices_share_colours() {
        let mesh = RawMesh {
            vertices: vec![[-1., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
            triangles: vec![[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]],
        };
        let map = vec![1, 0, 2, -1];
        let colours = correspondence_colours(&mesh.vertices, &map);
        assert_eq!(colours[0], colours[1]);
        assert_eq!(colours[3], OUTSIDE);
        let path = crate::test_dir("ply").join("out.ply");
        write_ply(&path, &mesh, &colours, &[0.5, 0.5, 1.0, 0.0]).unwrap();
        let back = read_mesh(&path).unwrap();
        assert_eq!(back.triangles, mesh.triangles);
        assert_eq!(back.vertices, mesh.vertices);
        let text = std::fs::read(&path).unwrap();
        let header = String::from_utf8_lossy(&text[..text.len().min(600)]);
        assert!(header.contains("property float quality") && header.contains("property uchar red"));
        // The records: 19 bytes per vertex (colour at 12, quality at 15), 13 per triangle.
        let body = header.find("end_header\n").unwrap() + "end_header\n".len();
        assert_eq!(text.len(), body + 4 * 19 + 4 * 13);
        let vertex = |i: usize| &text[body + 19 * i..body + 19 * (i + 1)];
        assert_eq!(vertex(1)[12..15], colours[1]);
        assert_eq!(f32::from_le_bytes(vertex(2)[15..19].try_into().unwrap()), 1.0);
        std::fs::remove_file(&path).unwrap();
    }
}
