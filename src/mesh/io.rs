//! Mesh files: OFF, PLY (ASCII and binary), OBJ and STL (ASCII and binary) in; the input's
//! vertex order is kept (STL has none: its vertices are numbered in order of first use).
//!
//! PLY goes through the `ply-rs-bw` crate (the maintained fork of `ply-rs`), STL through
//! `stl_io` (with the binary/ASCII decision made here, by size). OFF and OBJ have
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
    /// The extension is not one of off, ply, obj, stl.
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
                write!(f, "{}: unknown mesh format (expected .off, .ply, .obj or .stl)", path.display())
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

/// Reads an OFF, PLY, OBJ or STL file (chosen by extension, case-insensitive).
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
        Some("stl") => read_stl(reader).map_err(|m| parse(None, m)),
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

/// Calls `f(number, line)` on the lines of a text mesh file, numbered from 1, until the end or
/// `f`'s first error: a UTF-8 byte-order mark before the first line is dropped (issue 16, item
/// 5: an OBJ that starts with one lost its first vertex), a trailing `\r` too, and bytes that
/// are not UTF-8 become U+FFFD instead of failing the file (a Latin-1 comment is common; in a
/// number they still fail, with the line named). A line is lent from one buffer, not copied:
/// an owned string per line and per token took 0.65 s to read a 955k-vertex OFF, 1.6 s an
/// OBJ (session 37).
fn for_each_line(mut reader: impl BufRead, mut f: impl FnMut(usize, &str) -> Result<(), LineError>) -> Result<(), LineError> {
    let mut number = 0;
    let mut bytes = Vec::new();
    loop {
        bytes.clear();
        match reader.read_until(b'\n', &mut bytes) {
            Ok(0) => return Ok(()),
            Err(e) => return Err((Some(number + 1), e.to_string())),
            Ok(_) => {
                number += 1;
                let mut line: &[u8] = &bytes;
                if number == 1 {
                    line = line.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(line);
                }
                while let [rest @ .., b'\n' | b'\r'] = line {
                    line = rest;
                }
                match std::str::from_utf8(line) {
                    Ok(text) => f(number, text)?,
                    Err(_) => f(number, &String::from_utf8_lossy(line))?,
                }
            }
        }
    }
}

/// Where [`read_off`] is in the file.
enum OffPart {
    Header,
    Counts,
    Vertices { left: i64 },
    Faces { left: i64 },
    End,
}

/// OFF (also COFF/NOFF/…): header, counts, vertices (extra columns ignored), polygons. A
/// record after the counted faces is an error: the counts in the header are wrong, and faces
/// would be dropped silently (issue 16, item 5).
pub fn read_off(reader: impl BufRead) -> Result<RawMesh, LineError> {
    // Records are the non-empty lines, comments stripped; parsed as they are read (a token list
    // of the whole file took seconds and gigabytes on 10⁶ vertices).
    let num = |s: &str, l: usize| s.parse::<i64>().map_err(|_| (Some(l), format!("expected an integer, got {s:?}")));
    let mut mesh = RawMesh::default();
    let (mut nv, mut nf) = (0i64, 0i64);
    let mut part = OffPart::Header;
    let mut poly = Vec::new();
    for_each_line(reader, |l, line| {
        let record = line.split('#').next().unwrap_or("");
        let mut rec: smallvec::SmallVec<[&str; 8]> = record.split_whitespace().collect();
        if rec.is_empty() {
            return Ok(());
        }
        if let OffPart::Header = part {
            if !rec[0].ends_with("OFF") {
                return Err((Some(l), "missing OFF header".into()));
            }
            rec.remove(0);
            part = OffPart::Counts;
            if rec.is_empty() {
                return Ok(());
            }
        }
        match part {
            // (The header was read above: here `Header` cannot occur.)
            OffPart::Header | OffPart::Counts => {
                if rec.len() < 2 {
                    return Err((Some(l), "expected vertex and face counts".into()));
                }
                nv = num(rec[0], l)?;
                nf = num(rec[1], l)?;
                if nv < 0 || nf < 0 {
                    return Err((Some(l), "negative count".into()));
                }
                // Capacity from the header, bounded: a wrong count must not allocate gigabytes.
                mesh.vertices.reserve((nv as usize).min(1 << 24));
                mesh.triangles.reserve((nf as usize).min(1 << 25));
                part = if nv > 0 { OffPart::Vertices { left: nv } } else if nf > 0 { OffPart::Faces { left: nf } } else { OffPart::End };
            }
            OffPart::Vertices { left } => {
                if rec.len() < 3 {
                    return Err((Some(l), "vertex needs 3 coordinates".into()));
                }
                let mut p = [0.0; 3];
                for d in 0..3 {
                    p[d] = rec[d].parse().map_err(|_| (Some(l), format!("bad coordinate {:?}", rec[d])))?;
                }
                mesh.vertices.push(p);
                part = if left > 1 { OffPart::Vertices { left: left - 1 } } else if nf > 0 { OffPart::Faces { left: nf } } else { OffPart::End };
            }
            OffPart::Faces { left } => {
                let k = num(rec[0], l)?;
                if k < 0 || rec.len() < 1 + k as usize {
                    return Err((Some(l), "face record shorter than its vertex count".into()));
                }
                poly.clear();
                for s in &rec[1..=k as usize] {
                    poly.push(num(s, l).and_then(|x| to_index(x, l))?);
                }
                push_polygon(&mut mesh.triangles, &poly).map_err(|m| (Some(l), m))?;
                part = if left > 1 { OffPart::Faces { left: left - 1 } } else { OffPart::End };
            }
            OffPart::End => {
                return Err((Some(l), format!("a record after the {nf} faces the header counts: the header's counts are wrong (faces would be lost)")));
            }
        }
        Ok(())
    })?;
    match part {
        OffPart::Header => Err((None, "empty file".to_string())),
        OffPart::Counts => Err((None, "missing counts".to_string())),
        OffPart::Vertices { .. } => Err((None, format!("file ends before its {nv} vertices"))),
        OffPart::Faces { .. } => Err((None, format!("file ends before its {nf} faces"))),
        OffPart::End => Ok(mesh),
    }
}

/// OBJ: `v x y z` and `f a b c …` records (`a`, `a/t`, `a//n`, `a/t/n`; negative = relative).
/// Errors quote indices as the file writes them (1-based, as numbers: `007` is quoted `7`), and
/// an index beyond the vertices is caught here, with its line, not later in 0-based terms. A
/// `#` starts a comment anywhere on a line (`f 1 2 3 # lid` was refused until session 37).
pub fn read_obj(reader: impl BufRead) -> Result<RawMesh, LineError> {
    let mut mesh = RawMesh::default();
    // Faces as written, resolved once every vertex is known: each face's line, the vertices
    // read before it (what a relative index counts back from) and its range in `written`.
    let mut faces: Vec<(usize, i64, std::ops::Range<usize>)> = Vec::new();
    let mut written: Vec<i64> = Vec::new();
    for_each_line(reader, |l, line| {
        let mut rec = line.split('#').next().unwrap_or("").split_whitespace();
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
                let start = written.len();
                for s in rec {
                    let v = s.split('/').next().unwrap_or("");
                    written.push(v.parse().map_err(|_| (Some(l), format!("bad face index {s:?}")))?);
                }
                faces.push((l, mesh.vertices.len() as i64, start..written.len()));
            }
            _ => {}
        }
        Ok(())
    })?;
    let n = mesh.vertices.len() as i64;
    let mut poly = Vec::new();
    for (l, before, range) in faces {
        poly.clear();
        for &w in &written[range] {
            // Relative indices count back from the vertices read so far.
            let x = if w < 0 { before + w + 1 } else { w };
            if !(1..=n).contains(&x) {
                return Err((Some(l), format!("vertex index {w} is out of range: the file has vertices 1 to {n}")));
            }
            poly.push((x - 1) as u32);
        }
        push_polygon(&mut mesh.triangles, &poly).map_err(|m| (Some(l), m))?;
    }
    Ok(mesh)
}

/// STL, binary or ASCII (through the `stl_io` crate): three corners per triangle. Corners with
/// the same coordinates (to the bit) become one vertex, as an indexed format would write them;
/// a triangle two of whose corners coincide keeps its own copy of the repeated corner, so that
/// validation welds the copy and drops the collapsed triangle, counted ([`super::Mesh::new`]),
/// instead of refusing the file for a triangle that names a vertex twice. Binary when the size
/// is exactly 84 + 50 × the count at byte 80, else ASCII, whose first line must start with
/// `solid` (a binary file's free header may begin with `solid` too, so the text is not the
/// test; `stl_io`'s own probe takes such a file for ASCII and fails, and wants a name after
/// `solid`).
pub fn read_stl(mut reader: impl Read) -> Result<RawMesh, String> {
    // The whole file: binary or ASCII is told by its size (one copy; 50 bytes a triangle).
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    let binary = bytes.len() >= 84 && {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
        bytes.len() as u64 == 84 + 50 * count
    };
    let stl_error = |e: std::io::Error| format!("invalid STL: {e}");
    // What `stl_io` is given: a binary file with its free header blanked (its probe reads a
    // header that begins with "solid " as ASCII), an ASCII one with a named first line.
    let source = if binary {
        bytes[..80].fill(0);
        bytes
    } else {
        let text = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
        let first_end = text.iter().position(|&b| b == b'\n').map_or(text.len(), |i| i + 1);
        if !text[..first_end].starts_with(b"solid") {
            return Err(format!(
                "neither binary STL ({} bytes, where 84 + 50 per triangle were expected) nor ASCII STL (the first line does not start with \"solid\")",
                bytes.len()
            ));
        }
        let mut named = b"solid intrinsym\n".to_vec();
        named.extend_from_slice(&text[first_end..]);
        named
    };
    let mut cursor = std::io::Cursor::new(source);
    // The corners merged here, not by the crate's `as_indexed_triangles` (the same bit-exact
    // merge): that keeps every face with its normal and `usize` indices (40 bytes a triangle,
    // 76 MB at 1.9M) and f32 vertices to convert again, and its faces would still need their
    // repeated corners split off.
    let mut mesh = RawMesh::default();
    let mut index: std::collections::HashMap<[u32; 3], u32> = std::collections::HashMap::new();
    for t in stl_io::create_stl_reader(&mut cursor).map_err(stl_error)? {
        let t = t.map_err(stl_error)?;
        let mut corners = [0u32; 3];
        for (c, v) in corners.iter_mut().zip(&t.vertices) {
            let p = [v[0] as f64, v[1] as f64, v[2] as f64];
            *c = *index.entry(v.0.map(f32::to_bits)).or_insert_with(|| {
                mesh.vertices.push(p);
                (mesh.vertices.len() - 1) as u32
            });
        }
        // A repeated corner gets a copy of its own (welded and dropped by validation).
        for k in 1..3 {
            if corners[..k].contains(&corners[k]) {
                mesh.vertices.push(mesh.vertices[corners[k] as usize]);
                corners[k] = (mesh.vertices.len() - 1) as u32;
            }
        }
        mesh.triangles.push(corners);
    }
    Ok(mesh)
}

/// One record of a PLY element as [`read_ply`] keeps it: the coordinates and the index list,
/// whatever other properties the record has (they are dropped as they are read). The parser's
/// own `DefaultElement` keeps every record as a hash map of named properties: reading a
/// 955k-vertex PLY took 1.1 GiB and 10 s more than the same mesh as OFF (issue 17).
#[derive(Default)]
struct PlyRecord {
    xyz: [f64; 3],
    /// Bits 0–2: x, y, z present; bit 3: an index list present; bit 4: a list that is not of
    /// integers.
    found: u8,
    indices: smallvec::SmallVec<[i64; 4]>,
}

impl ply_rs_bw::ply::PropertyAccess for PlyRecord {
    fn new() -> Self {
        Self::default()
    }
    fn set_property(&mut self, name: &str, property: ply_rs_bw::ply::Property) -> ply_rs_bw::ply::PropertyAccessResult {
        use ply_rs_bw::ply::{Property, PropertyAccessResult};
        if let Some(d) = ["x", "y", "z"].iter().position(|c| *c == name) {
            let value = match property {
                Property::Char(x) => x as f64,
                Property::UChar(x) => x as f64,
                Property::Short(x) => x as f64,
                Property::UShort(x) => x as f64,
                Property::Int(x) => x as f64,
                Property::UInt(x) => x as f64,
                Property::Float(x) => x as f64,
                Property::Double(x) => x,
                _ => return PropertyAccessResult::Ignored,
            };
            self.xyz[d] = value;
            self.found |= 1 << d;
        } else if name == "vertex_indices" || (name == "vertex_index" && self.found & 8 == 0) {
            self.found |= 8;
            self.indices.clear();
            match property {
                Property::ListChar(v) => self.indices.extend(v.iter().map(|&x| x as i64)),
                Property::ListUChar(v) => self.indices.extend(v.iter().map(|&x| x as i64)),
                Property::ListShort(v) => self.indices.extend(v.iter().map(|&x| x as i64)),
                Property::ListUShort(v) => self.indices.extend(v.iter().map(|&x| x as i64)),
                Property::ListInt(v) => self.indices.extend(v.iter().map(|&x| x as i64)),
                Property::ListUInt(v) => self.indices.extend(v.iter().map(|&x| x as i64)),
                _ => self.found |= 16,
            }
        } else {
            return PropertyAccessResult::Ignored;
        }
        PropertyAccessResult::Set
    }
}

/// PLY, ASCII or binary, through `ply-rs-bw`: element `vertex` (x, y, z) and `face`
/// (`vertex_indices` or `vertex_index`, any integer list type).
pub fn read_ply(mut reader: impl Read) -> Result<RawMesh, String> {
    use ply_rs_bw::parser::Parser;
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    let body = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
    check_ply_counts(body)?;
    let mut ply = Parser::<PlyRecord>::new().read_ply(&mut &body[..]).map_err(|e| e.to_string())?;
    drop(bytes);
    let mut mesh = RawMesh::default();
    let verts = ply.payload.swap_remove("vertex").ok_or("no 'vertex' element")?;
    mesh.vertices.reserve(verts.len());
    for (i, v) in verts.iter().enumerate() {
        if let Some(d) = (0..3).find(|&d| v.found & (1 << d) == 0) {
            return Err(format!("vertex {i} has no numeric '{}'", ["x", "y", "z"][d]));
        }
        mesh.vertices.push(v.xyz);
    }
    drop(verts);
    if let Some(faces) = ply.payload.swap_remove("face") {
        mesh.triangles.reserve(faces.len());
        let mut poly = Vec::new();
        for (i, f) in faces.iter().enumerate() {
            if f.found & 8 == 0 {
                return Err(format!("face {i} has no 'vertex_indices'"));
            }
            if f.found & 16 != 0 {
                return Err(format!("face {i}: 'vertex_indices' is not an integer list"));
            }
            poly.clear();
            for &x in &f.indices {
                poly.push(u32::try_from(x).map_err(|_| format!("face {i}: vertex index {x} is out of range"))?);
            }
            push_polygon(&mut mesh.triangles, &poly).map_err(|m| format!("face {i}: {m}"))?;
        }
    }
    Ok(mesh)
}

/// Refuses a PLY header whose element counts cannot fit in the file: the parser reserves memory
/// for every declared record up front, so a 71-byte file declaring 4·10⁹ records aborted the
/// process for lack of memory (issue 16, item 5). Each record takes at least one byte (its
/// scalar properties' sizes and each list's count in binary; a separator per property in ASCII).
fn check_ply_counts(bytes: &[u8]) -> Result<(), String> {
    let end = bytes.windows(10).position(|w| w == b"end_header").ok_or("no 'end_header' line in the PLY header")?;
    let header = String::from_utf8_lossy(&bytes[..end]);
    let body_start = bytes[end..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |i| end + i + 1);
    let body = bytes.len() - body_start;
    let binary = header.lines().any(|l| l.starts_with("format binary"));
    let size = |t: &str| match t {
        "char" | "uchar" | "int8" | "uint8" => 1,
        "short" | "ushort" | "int16" | "uint16" => 2,
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => 4,
        "double" | "float64" => 8,
        _ => 1,
    };
    // (name, count, least bytes per record)
    let mut elements: Vec<(String, u64, u64)> = Vec::new();
    for line in header.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["element", name, count] => {
                let count = count.parse::<u64>().map_err(|_| format!("element '{name}' has a bad count {count:?}"))?;
                elements.push((name.to_string(), count, 0));
            }
            ["property", "list", count_type, _, _] => {
                if let Some(e) = elements.last_mut() {
                    e.2 += if binary { size(count_type) } else { 2 };
                }
            }
            ["property", scalar, _] => {
                if let Some(e) = elements.last_mut() {
                    e.2 += if binary { size(scalar) } else { 2 };
                }
            }
            _ => {}
        }
    }
    let mut needed: u64 = 0;
    for (name, count, least) in &elements {
        needed = needed.saturating_add(count.saturating_mul((*least).max(1)));
        if needed > body as u64 {
            return Err(format!("the header declares {count} '{name}' records, more than the {body} bytes after the header can hold (a truncated or corrupt file)"));
        }
    }
    Ok(())
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
        // A comment may follow a record.
        let s = "v 0 0 0 # origin\nv 1 0 0\nv 1 1 0\nv 0 1 0.5#top\nf 1 2 3 4 # the quad\n";
        assert_eq!(read_obj(s.as_bytes()).unwrap(), quad());
    }

    /// The file's end before what the header promised, named (the readers stream lines; these
    /// are the errors found after the last one).
    #[test]
    fn off_ends_early() {
        let end = |s: &str| read_off(s.as_bytes()).unwrap_err();
        assert_eq!(end(""), (None, "empty file".to_string()));
        assert_eq!(end("# only a comment\n\n"), (None, "empty file".to_string()));
        assert_eq!(end("OFF\n"), (None, "missing counts".to_string()));
        assert_eq!(end("OFF\n3 1 0\n0 0 0\n"), (None, "file ends before its 3 vertices".to_string()));
        assert_eq!(end("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"), (None, "file ends before its 1 faces".to_string()));
        assert_eq!(end("OFF\n-1 0 0\n"), (Some(2), "negative count".to_string()));
        assert_eq!(end("OFF\n3\n"), (Some(2), "expected vertex and face counts".to_string()));
        // No vertices and no faces is a file read (the mesh is refused later, as empty).
        assert_eq!(read_off("OFF\n0 0 0\n".as_bytes()).unwrap(), RawMesh::default());
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

    /// Issue 16, item 5: files as users have them.
    #[test]
    fn byte_order_marks_latin1_comments_and_wrong_counts() {
        // A UTF-8 byte-order mark does not swallow the first vertex.
        let s = "\u{feff}v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nf 1 2 3 4\n";
        assert_eq!(read_obj(s.as_bytes()).unwrap(), quad());
        let s = "\u{feff}OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n";
        assert_eq!(read_off(s.as_bytes()).unwrap(), quad());
        // A Latin-1 byte in a comment is not an error; in a number it is, with its line.
        let mut latin = b"OFF\n# caf\xE9\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n".to_vec();
        assert_eq!(read_off(&latin[..]).unwrap(), quad());
        latin[17] = 0xE9;
        assert_eq!(read_off(&latin[..]).unwrap_err().0, Some(4));
        // More faces than the header counts: refused, not silently dropped.
        let e = read_off("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n3 0 1 2\n3 0 2 3\n".as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(8));
        assert!(e.1.contains("header"), "{}", e.1);
        // OBJ indices are quoted as written (1-based), with the line.
        let e = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n".as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(4));
        assert!(e.1.contains("vertex index 4") && e.1.contains("1 to 3"), "{}", e.1);
        let e = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n".as_bytes()).unwrap_err();
        assert!(e.1.contains("vertex index -4"), "{}", e.1);
    }

    /// STL, binary and ASCII: a tetrahedron as a triangle soup becomes 4 shared vertices; a
    /// binary header that begins with "solid" is still binary; an ASCII file whose first line
    /// names nothing is read; a triangle with two equal corners is welded away and counted by
    /// validation, not refused; neither format (or a binary whose size disagrees with its
    /// count) is an error that says so, without allocating what the count claims.
    #[test]
    fn stl_binary_and_ascii() {
        let p = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let tets = [[0usize, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let binary = |header: &[u8], tris: &[[[f32; 3]; 3]]| {
            let mut b = vec![0u8; 80];
            b[..header.len()].copy_from_slice(header);
            b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
            for t in tris {
                b.extend_from_slice(&[0u8; 12]);
                for c in t {
                    for x in c {
                        b.extend_from_slice(&x.to_le_bytes());
                    }
                }
                b.extend_from_slice(&[0u8; 2]);
            }
            b
        };
        let soup: Vec<[[f32; 3]; 3]> = tets.iter().map(|t| t.map(|i| p[i])).collect();
        let check = |m: &RawMesh| {
            assert_eq!(m.vertices.len(), 4);
            assert_eq!(m.triangles.len(), 4);
            let mesh = crate::Mesh::new(m.vertices.clone(), m.triangles.clone(), &crate::MeshParams::default()).unwrap();
            assert_eq!(mesh.num_vertices(), 4);
        };
        check(&read_stl(&binary(b"solid but binary", &soup)[..]).unwrap());
        let mut ascii = String::from("solid\r\n");
        for t in &soup {
            ascii += "facet normal 0 0 0\n outer loop\n";
            for c in t {
                ascii += &format!("  vertex {} {} {}\n", c[0], c[1], c[2]);
            }
            ascii += " endloop\nendfacet\n";
        }
        ascii += "endsolid\n";
        check(&read_stl(ascii.as_bytes()).unwrap());
        // A degenerate fifth triangle (two corners equal): read, then welded away and counted.
        let mut five = soup.clone();
        five.push([p[0], p[1], p[1]]);
        let m = read_stl(&binary(b"", &five)[..]).unwrap();
        assert_eq!((m.vertices.len(), m.triangles.len()), (5, 5));
        let mesh = crate::Mesh::new(m.vertices, m.triangles, &crate::MeshParams::default()).unwrap();
        assert_eq!((mesh.num_vertices(), mesh.triangles.len(), mesh.info.collapsed_triangles), (4, 4, 1));
        // Neither format; a binary whose count claims 4·10⁹ triangles in 84 bytes.
        assert!(read_stl(&b"OFF\n3 1 0\n"[..]).unwrap_err().contains("neither binary STL"));
        let mut bomb = binary(b"", &[]);
        bomb[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        assert!(read_stl(&bomb[..]).unwrap_err().contains("84 + 50 per triangle"));
        // A truncated ASCII file is an error of the STL reader.
        assert!(read_stl(&ascii.as_bytes()[..ascii.len() / 2]).unwrap_err().starts_with("invalid STL"));
    }

    /// Issue 16, item 5: a 71-byte binary PLY whose header declares 4·10⁹ property-less
    /// records aborted the process (the parser reserved 4.5 GB); it is refused.
    #[test]
    fn ply_counts_larger_than_the_file_are_refused() {
        let bomb = b"ply\nformat binary_little_endian 1.0\nelement junk 4000000000\nend_header\n";
        let e = read_ply(&bomb[..]).unwrap_err();
        assert!(e.contains("4000000000") && e.contains("junk"), "{e}");
        let short = "ply\nformat ascii 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
        assert!(read_ply(short.as_bytes()).unwrap_err().contains("vertex"));
        // A byte-order mark and CRLF line ends are accepted.
        let crlf = "\u{feff}ply\r\nformat ascii 1.0\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\nproperty double z\r\n\
                    element face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0.5\r\n4 0 1 2 3\r\n";
        assert_eq!(read_ply(crlf.as_bytes()).map_err(|e| e.to_string()), Ok(quad()));
    }

    #[test]
    fn read_mesh_dispatches_and_reports_paths() {
        let dir = crate::test_dir("io");
        let off = dir.join("q.OFF");
        std::fs::write(&off, "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.5\n4 0 1 2 3\n").unwrap();
        assert_eq!(read_mesh(&off).unwrap(), quad());
        let copy = dir.join("copy.off");
        write_off(&copy, &quad().vertices, &quad().triangles).unwrap();
        let back = read_mesh(&copy).unwrap();
        assert_eq!(back.vertices, quad().vertices);
        assert_eq!(back.triangles, quad().triangles);
        let bad = dir.join("q.3ds");
        std::fs::write(&bad, "").unwrap();
        assert!(matches!(read_mesh(&bad), Err(IoError::UnknownFormat { .. })));
        let missing = dir.join("missing.off");
        let e = read_mesh(&missing).unwrap_err();
        assert!(e.to_string().contains("missing.off"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
