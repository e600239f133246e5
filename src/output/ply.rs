//! Coloured PLY output (binary little endian, through `ply-rs-bw`): per-vertex colour and a
//! float `quality` property, which MeshLab reads as vertex quality.
//!
//! Colouring ([`correspondence_colours`]): a vertex and its image under the chosen symmetry get
//! the same colour — a symmetric function of `p(v)` and `p(T v)`: per channel, their mean and
//! the mean of their squares, in bounding-box coordinates mapped to [−1, 1] — so mirrored
//! parts are painted alike; vertices outside the region are grey. The squares matter where the
//! mean says nothing: a sphere's antipodal map sends every midpoint to the centre, and the
//! midpoint alone painted the whole sphere one colour (issue 16, item 21).

use std::path::Path;

use ply_rs_bw::ply::{Addable, DefaultElement, ElementDef, Encoding, Ply, Property, PropertyDef, PropertyType, ScalarType};
use ply_rs_bw::writer::Writer;

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
pub fn write_ply(path: impl AsRef<Path>, mesh: &RawMesh, colours: &[[u8; 3]], quality: &[f64]) -> Result<(), IoError> {
    let path = path.as_ref();
    let mut ply = Ply::<DefaultElement>::new();
    ply.header.encoding = Encoding::BinaryLittleEndian;
    ply.header.comments.push("written by intrinsym: colour = symmetry correspondence, quality = symmetry confidence".into());
    let mut vertex = ElementDef::new("vertex".to_string());
    for name in ["x", "y", "z"] {
        vertex.properties.add(PropertyDef::new(name.to_string(), PropertyType::Scalar(ScalarType::Float)));
    }
    for name in ["red", "green", "blue"] {
        vertex.properties.add(PropertyDef::new(name.to_string(), PropertyType::Scalar(ScalarType::UChar)));
    }
    vertex.properties.add(PropertyDef::new("quality".to_string(), PropertyType::Scalar(ScalarType::Float)));
    ply.header.elements.add(vertex);
    let mut face = ElementDef::new("face".to_string());
    face.properties.add(PropertyDef::new("vertex_indices".to_string(), PropertyType::List(ScalarType::UChar, ScalarType::Int)));
    ply.header.elements.add(face);
    let verts = mesh
        .vertices
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut e = DefaultElement::new();
            e.insert("x".into(), Property::Float(p[0] as f32));
            e.insert("y".into(), Property::Float(p[1] as f32));
            e.insert("z".into(), Property::Float(p[2] as f32));
            let c = colours.get(i).copied().unwrap_or(OUTSIDE);
            e.insert("red".into(), Property::UChar(c[0]));
            e.insert("green".into(), Property::UChar(c[1]));
            e.insert("blue".into(), Property::UChar(c[2]));
            e.insert("quality".into(), Property::Float(quality.get(i).copied().unwrap_or(0.0) as f32));
            e
        })
        .collect();
    ply.payload.insert("vertex".into(), verts);
    let faces = mesh
        .triangles
        .iter()
        .map(|t| {
            let mut e = DefaultElement::new();
            e.insert("vertex_indices".into(), Property::ListInt(t.iter().map(|&i| i as i32).collect()));
            e
        })
        .collect();
    ply.payload.insert("face".into(), faces);
    let file = std::fs::File::create(path).map_err(|source| IoError::Os { path: path.into(), source })?;
    let mut w = std::io::BufWriter::new(file);
    Writer::new()
        .write_ply(&mut w, &mut ply)
        .map_err(|source| IoError::Os { path: path.into(), source })?;
    Ok(())
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
        let header = String::from_utf8_lossy(&text[..300]);
        assert!(header.contains("property float quality") && header.contains("property uchar red"));
        std::fs::remove_file(&path).unwrap();
    }
}
