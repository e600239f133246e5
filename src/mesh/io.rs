//! Mesh files: OFF, PLY (ASCII and binary) and OBJ in; the input's vertex order is kept.
//!
//! PLY goes through the `ply-rs-bw` crate (the maintained fork of `ply-rs`). OFF and OBJ have
//! small readers here: no maintained OFF crate exists, and `tobj` renumbers vertices per object in
//! order of first use, which would break our promise that result indices are the input file's.
//! Polygons are fan-triangulated; OBJ texture/normal indices, colours and normals are ignored.

use std::fmt;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

/// A mesh as read from a file, before validation ([`super::Mesh::new`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawMesh {
    /// `(n, 3)` vertex positions in file order.
    pub vertices: Vec<[f64; 3]>,
    /// `(m, 3)` triangles (polygons fan-triangulated), 0-based indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

/// A mesh file could not be read.
#[derive(Debug)]
#[non_exhaustive]
pub enum IoError {
    /// The operating system refused (missing file, permissions, …).
    Os {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The extension is not one of off, ply, obj.
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// The file's contents are malformed.
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line, where known.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
}

impl fmt::Display for IoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IoError::Os { path, source } => write!(f, "{}: {source}", path.display()),
            IoError::UnknownFormat { path } => {
                write!(f, "{}: unknown mesh format (expected .off, .ply or .obj)", path.display())
            }
            IoError::Parse { path, line: Some(l), message } => write!(f, "{}:{l}: {message}", path.display()),
            IoError::Parse { path, line: None, message } => write!(f, "{}: {message}", path.display()),
        }
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            IoError::Os { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Reads an OFF, PLY or OBJ file (chosen by extension, case-insensitive).
pub fn read_mesh(path: impl AsRef<Path>) -> Result<RawMesh, IoError> {
    let path = path.as_ref();
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let file = std::fs::File::open(path).map_err(|source| IoError::Os { path: path.into(), source })?;
    let reader = BufReader::new(file);
    let parse = |line, message: String| IoError::Parse { path: path.into(), line, message };
    match ext.as_deref() {
        Some("off") => read_off(reader).map_err(|(l, m)| parse(l, m)),
        Some("obj") => read_obj(reader).map_err(|(l, m)| parse(l, m)),
        Some("ply") => read_ply(reader).map_err(|m| parse(None, m)),
        _ => Err(IoError::UnknownFormat { path: path.into() }),
    }
}

type LineError = (Option<usize>, String);

/// Appends the fan triangulation of `poly` (already 0-based).
fn push_polygon(out: &mut Vec<[u32; 3]>, poly: &[u32]) -> Result<(), String> {
    if poly.len() < 3 {
        return Err(format!("face with {} vertices (at least 3 needed)", poly.len()));
    }
    for k in 1..poly.len() - 1 {
        out.push([poly[0], poly[k], poly[k + 1]]);
    }
    Ok(())
}

fn to_index(x: i64, line: usize) -> Result<u32, LineError> {
    u32::try_from(x).map_err(|_| (Some(line), format!("vertex index {x} is out of range")))
}

/// OFF (also COFF/NOFF/…): header, counts, vertices (extra columns ignored), polygons.
pub fn read_off(reader: impl BufRead) -> Result<RawMesh, LineError> {
    // Tokens with their line numbers, comments stripped.
    let mut tokens = Vec::new();
    for (i, line) in reader.lines().enumerate() {
        let line = line.map_err(|e| (Some(i + 1), e.to_string()))?;
        let line = line.split('#').next().unwrap_or("");
        tokens.extend(line.split_whitespace().map(|t| (i + 1, t.to_owned())));
    }
    // Group tokens back into lines: vertex and face records are one per line.
    let mut lines: Vec<(usize, Vec<String>)> = Vec::new();
    for (l, t) in tokens {
        match lines.last_mut() {
            Some((ll, v)) if *ll == l => v.push(t),
            _ => lines.push((l, vec![t])),
        }
    }
    let mut it = lines.into_iter();
    let (l0, mut first) = it.next().ok_or((None, "empty file".to_string()))?;
    if !first[0].ends_with("OFF") {
        return Err((Some(l0), "missing OFF header".into()));
    }
    first.remove(0);
    let counts = if first.is_empty() { it.next().ok_or((None, "missing counts".to_string()))? } else { (l0, first) };
    let num = |s: &str, l: usize| s.parse::<i64>().map_err(|_| (Some(l), format!("expected an integer, got {s:?}")));
    if counts.1.len() < 2 {
        return Err((Some(counts.0), "expected vertex and face counts".into()));
    }
    let nv = num(&counts.1[0], counts.0)?;
    let nf = num(&counts.1[1], counts.0)?;
    if nv < 0 || nf < 0 {
        return Err((Some(counts.0), "negative count".into()));
    }
    let mut mesh = RawMesh::default();
    for _ in 0..nv {
        let (l, rec) = it.next().ok_or((None, format!("file ends before its {nv} vertices")))?;
        if rec.len() < 3 {
            return Err((Some(l), "vertex needs 3 coordinates".into()));
        }
        let mut p = [0.0; 3];
        for d in 0..3 {
            p[d] = rec[d].parse().map_err(|_| (Some(l), format!("bad coordinate {:?}", rec[d])))?;
        }
        mesh.vertices.push(p);
    }
    for _ in 0..nf {
        let (l, rec) = it.next().ok_or((None, format!("file ends before its {nf} faces")))?;
        let k = num(&rec[0], l)?;
        if k < 0 || rec.len() < 1 + k as usize {
            return Err((Some(l), "face record shorter than its vertex count".into()));
        }
        let poly = rec[1..=k as usize]
            .iter()
            .map(|s| num(s, l).and_then(|x| to_index(x, l)))
            .collect::<Result<Vec<_>, _>>()?;
        push_polygon(&mut mesh.triangles, &poly).map_err(|m| (Some(l), m))?;
    }
    Ok(mesh)
}

/// OBJ: `v x y z` and `f a b c …` records (`a`, `a/t`, `a//n`, `a/t/n`; negative = relative).
pub fn read_obj(reader: impl BufRead) -> Result<RawMesh, LineError> {
    let mut mesh = RawMesh::default();
    for (i, line) in reader.lines().enumerate() {
        let l = i + 1;
        let line = line.map_err(|e| (Some(l), e.to_string()))?;
        let mut rec = line.split_whitespace();
        match rec.next() {
            Some("v") => {
                let mut p = [0.0; 3];
                for x in &mut p {
                    let s = rec.next().ok_or((Some(l), "vertex needs 3 coordinates".to_string()))?;
                    *x = s.parse().map_err(|_| (Some(l), format!("bad coordinate {s:?}")))?;
                }
                mesh.vertices.push(p);
            }
            Some("f") => {
                let n = mesh.vertices.len() as i64;
                let poly = rec
                    .map(|s| {
                        let v = s.split('/').next().unwrap_or("");
                        let x: i64 = v.parse().map_err(|_| (Some(l), format!("bad face index {s:?}")))?;
                        let x = if x < 0 { n + x } else { x - 1 };
                        to_index(x, l)
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                push_polygon(&mut mesh.triangles, &poly).map_err(|m| (Some(l), m))?;
            }
            _ => {}
        }
    }
    Ok(mesh)
}

/// PLY, ASCII or binary, through `ply-rs-bw`: element `vertex` (x, y, z) and `face`
/// (`vertex_indices` or `vertex_index`, any integer list type).
pub fn read_ply(mut reader: impl Read) -> Result<RawMesh, String> {
    use ply_rs_bw::parser::Parser;
    use ply_rs_bw::ply::{DefaultElement, Property};
    let ply = Parser::<DefaultElement>::new().read_ply(&mut reader).map_err(|e| e.to_string())?;
    let scalar = |p: &Property| -> Option<f64> {
        Some(match *p {
            Property::Char(x) => x as f64,
            Property::UChar(x) => x as f64,
            Property::Short(x) => x as f64,
            Property::UShort(x) => x as f64,
            Property::Int(x) => x as f64,
            Property::UInt(x) => x as f64,
            Property::Float(x) => x as f64,
            Property::Double(x) => x,
            _ => return None,
        })
    };
    let mut mesh = RawMesh::default();
    let verts = ply.payload.get("vertex").ok_or("no 'vertex' element")?;
    for (i, v) in verts.iter().enumerate() {
        let mut p = [0.0; 3];
        for (d, name) in ["x", "y", "z"].iter().enumerate() {
            p[d] = v.get(*name).and_then(scalar).ok_or_else(|| format!("vertex {i} has no numeric '{name}'"))?;
        }
        mesh.vertices.push(p);
    }
    if let Some(faces) = ply.payload.get("face") {
        for (i, f) in faces.iter().enumerate() {
            let list = f
                .get("vertex_indices")
                .or_else(|| f.get("vertex_index"))
                .ok_or_else(|| format!("face {i} has no 'vertex_indices'"))?;
            let idx: Vec<i64> = match list {
                Property::ListChar(v) => v.iter().map(|&x| x as i64).collect(),
                Property::ListUChar(v) => v.iter().map(|&x| x as i64).collect(),
                Property::ListShort(v) => v.iter().map(|&x| x as i64).collect(),
                Property::ListUShort(v) => v.iter().map(|&x| x as i64).collect(),
                Property::ListInt(v) => v.iter().map(|&x| x as i64).collect(),
                Property::ListUInt(v) => v.iter().map(|&x| x as i64).collect(),
                _ => return Err(format!("face {i}: 'vertex_indices' is not an integer list")),
            };
            let poly = idx
                .into_iter()
                .map(|x| u32::try_from(x).map_err(|_| format!("face {i}: vertex index {x} is out of range")))
                .collect::<Result<Vec<_>, _>>()?;
            push_polygon(&mut mesh.triangles, &poly).map_err(|m| format!("face {i}: {m}"))?;
        }
    }
    Ok(mesh)
}

/// Writes an ASCII OFF file (17 significant digits: coordinates round-trip exactly).
pub fn write_off(path: impl AsRef<Path>, vertices: &[[f64; 3]], triangles: &[[u32; 3]]) -> Result<(), IoError> {
    use std::io::Write;
    let path = path.as_ref();
    let os = |source| IoError::Os { path: path.into(), source };
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).map_err(os)?);
    writeln!(w, "OFF\n{} {} 0", vertices.len(), triangles.len()).map_err(os)?;
    for p in vertices {
        writeln!(w, "{:?} {:?} {:?}", p[0], p[1], p[2]).map_err(os)?;
    }
    for t in triangles {
        writeln!(w, "3 {} {} {}", t[0], t[1], t[2]).map_err(os)?;
    }
    w.flush().map_err(os)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> RawMesh {
        RawMesh {
            vertices: vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.5]],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn off_with_comments_quads_and_colours() {
        let s = "OFF # header\n# comment\n4 1 0\n0 0 0\n1 0 0 255 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3 7 7 7\n";
        assert_eq!(read_off(s.as_bytes()).unwrap(), quad());
        let s = "OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n";
        assert_eq!(read_off(s.as_bytes()).unwrap(), quad());
    }

    #[test]
    fn off_errors_name_the_line() {
        assert_eq!(read_off("PLY\n".as_bytes()).unwrap_err().0, Some(1));
        let e = read_off("OFF\n2 1 0\n0 0 0\n0 0 x\n".as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(4));
        let e = read_off("OFF\n3 1 0\n0 0 0\n0 0 1\n0 1 0\n3 0 1\n".as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(6));
        assert!(read_off("OFF\n3 2 0\n0 0 0\n0 0 1\n0 1 0\n3 0 1 2\n".as_bytes()).is_err());
        assert!(read_off("OFF\n3 1 0\n0 0 0\n0 0 1\n0 1 0\n3 0 1 -2\n".as_bytes()).is_err());
    }

    #[test]
    fn obj_index_forms() {
        let s = "# c\nv 0 0 0\nv 1 0 0\nvt 0 0\nv 1 1 0\nv 0 1 0.5\nf 1/1 2/1/1 3//1\nf -4 -2 -1\n";
        assert_eq!(read_obj(s.as_bytes()).unwrap(), quad());
        let s = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nf 1 2 3 4\n";
        assert_eq!(read_obj(s.as_bytes()).unwrap(), quad());
        assert_eq!(read_obj("v 0 0\n".as_bytes()).unwrap_err().0, Some(1));
        assert_eq!(read_obj("v 0 0 0\nf 1 2\n".as_bytes()).unwrap_err().0, Some(2));
        assert!(read_obj("v 0 0 0\nf 0 1 1\n".as_bytes()).is_err()); // OBJ is 1-based
    }

    #[test]
    fn ply_ascii_and_binary() {
        let ascii = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty double z\n\
                     element face 1\nproperty list uchar int vertex_indices\nend_header\n\
                     0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n";
        assert_eq!(read_ply(ascii.as_bytes()).unwrap(), quad());
        let mut bin = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\n\
                        property double z\nelement face 2\nproperty list uchar uint vertex_index\nend_header\n"
            .to_vec();
        for p in quad().vertices {
            for x in p {
                bin.extend_from_slice(&x.to_le_bytes());
            }
        }
        for t in quad().triangles {
            bin.push(3);
            for i in t {
                bin.extend_from_slice(&i.to_le_bytes());
            }
        }
        assert_eq!(read_ply(&bin[..]).unwrap(), quad());
        assert!(read_ply("ply\nformat ascii 1.0\nend_header\n".as_bytes()).is_err());
    }

    #[test]
    fn read_mesh_dispatches_and_reports_paths() {
        let dir = std::env::temp_dir().join(format!("intrinsym-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let off = dir.join("q.OFF");
        std::fs::write(&off, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n").unwrap();
        assert_eq!(read_mesh(&off).unwrap(), quad());
        let copy = dir.join("copy.off");
        write_off(&copy, &quad().vertices, &quad().triangles).unwrap();
        let back = read_mesh(&copy).unwrap();
        assert_eq!(back.vertices, quad().vertices);
        assert_eq!(back.triangles, quad().triangles);
        let bad = dir.join("q.stl");
        std::fs::write(&bad, "").unwrap();
        assert!(matches!(read_mesh(&bad), Err(IoError::UnknownFormat { .. })));
        let missing = dir.join("missing.off");
        let e = read_mesh(&missing).unwrap_err();
        assert!(e.to_string().contains("missing.off"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
