//! Scan point files, streamed: XYZ / CSV text, PLY (ASCII, binary little- and
//! big-endian) and LAS/LAZ (through `las_file`), read in chunks handed to a
//! callback and written from a slice.
//!
//! The PLY reader is our own (about a hundred lines): the `ply-rs` crate parses
//! a whole file into maps of properties per vertex, which for a scan of millions
//! of points is the copy this module exists to avoid. Only the `vertex` element's
//! `x`, `y`, `z` are read; other scalar properties (colour, intensity, normals)
//! are skipped, elements after the vertices (faces) are not read.

use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::Path;

use glam::DVec3;

use super::ScanError;
use super::error::bad;
use super::las_file::{MAGIC, read_las, write_las};

/// Points handed to the callback at a time.
pub const CHUNK: usize = 65_536;

/// A point file's format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointFormat {
    /// One point a line, `x y z` (spaces, tabs, commas or semicolons; more
    /// columns ignored; `#` comments and one header line skipped).
    Xyz,
    /// PLY, ASCII.
    PlyAscii,
    /// PLY, binary little-endian (the default for `.ply`).
    PlyBinary,
    /// ASPRS LAS 1.2, point format 0 (`.las`).
    Las,
    /// LAZ, compressed LAS (`.laz`).
    Laz,
}

impl PointFormat {
    /// The format a file name's extension implies (`.ply` binary unless
    /// `ascii`, `.las`, `.laz`, else XYZ text).
    pub fn of_path(path: &Path, ascii: bool) -> Self {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match (ext.as_deref(), ascii) {
            (Some("ply"), true) => PointFormat::PlyAscii,
            (Some("ply"), false) => PointFormat::PlyBinary,
            (Some("las"), _) => PointFormat::Las,
            (Some("laz"), _) => PointFormat::Laz,
            _ => PointFormat::Xyz,
        }
    }
}

/// Writes `points` to `path` in `format` (mm, six decimals in text, 0.001 mm
/// steps in LAS/LAZ).
///
/// # Errors
///
/// [`ScanError::Io`] when the file cannot be written.
pub fn write_points(path: &Path, format: PointFormat, points: &[DVec3]) -> Result<(), ScanError> {
    let io = |e| ScanError::io(path, e);
    let mut out = match format {
        PointFormat::Las => return write_las(path, points, false),
        PointFormat::Laz => return write_las(path, points, true),
        _ => BufWriter::new(File::create(path).map_err(io)?),
    };
    match format {
        PointFormat::Xyz => {
            for p in points {
                writeln!(out, "{:.6} {:.6} {:.6}", p.x, p.y, p.z).map_err(io)?;
            }
        }
        _ => {
            let kind = if format == PointFormat::PlyAscii {
                "ascii"
            } else {
                "binary_little_endian"
            };
            write!(
                out,
                "ply\nformat {kind} 1.0\ncomment vesselcad scan, mm\nelement vertex {}\n\
                 property double x\nproperty double y\nproperty double z\nend_header\n",
                points.len()
            )
            .map_err(io)?;
            for p in points {
                if format == PointFormat::PlyAscii {
                    writeln!(out, "{:.6} {:.6} {:.6}", p.x, p.y, p.z).map_err(io)?;
                } else {
                    for c in [p.x, p.y, p.z] {
                        out.write_all(&c.to_le_bytes()).map_err(io)?;
                    }
                }
            }
        }
    }
    out.flush().map_err(io)
}

/// Reads the points of `path` (format from its content: PLY by its magic line,
/// LAS/LAZ by `LASF`, else XYZ/CSV), handing them to `sink` in chunks of at
/// most [`CHUNK`].
/// Returns the number of points read.
///
/// # Errors
///
/// [`ScanError::Io`] when the file cannot be read, [`ScanError::Points`] (file,
/// line or byte offset, what) for malformed content.
pub fn read_points(path: &Path, mut sink: impl FnMut(&[DVec3])) -> Result<u64, ScanError> {
    let file = File::open(path).map_err(|e| ScanError::io(path, e))?;
    let mut reader = BufReader::with_capacity(1 << 20, file);
    let head = reader.fill_buf().map_err(|e| ScanError::io(path, e))?;
    if head.starts_with(b"ply") {
        read_ply(path, reader, &mut sink)
    } else if head.starts_with(MAGIC) {
        drop(reader);
        read_las(path, CHUNK, &mut sink)
    } else {
        read_xyz(path, reader, &mut sink)
    }
}

/// Reads every point of `path` into memory, once.
///
/// # Errors
///
/// As [`read_points`].
pub fn load_points(path: &Path) -> Result<Vec<DVec3>, ScanError> {
    let mut all = Vec::new();
    read_points(path, |chunk| all.extend_from_slice(chunk))?;
    Ok(all)
}

fn read_xyz(
    path: &Path,
    reader: impl BufRead,
    sink: &mut impl FnMut(&[DVec3]),
) -> Result<u64, ScanError> {
    let mut chunk = Vec::with_capacity(CHUNK);
    let mut count = 0u64;
    let mut seen_data = false;
    for (i, line) in reader.lines().enumerate() {
        let number = i as u64 + 1;
        let line = line.map_err(|e| ScanError::io(path, e))?;
        let text = line.trim();
        if text.is_empty() || text.starts_with('#') || text.starts_with("//") {
            continue;
        }
        let Some(point) = xyz_line(text, !seen_data).map_err(|m| bad(path, number, m))? else {
            // One header line (column names) before the data.
            seen_data = true;
            continue;
        };
        seen_data = true;
        chunk.push(point);
        count += 1;
        if chunk.len() == CHUNK {
            sink(&chunk);
            chunk.clear();
        }
    }
    if !chunk.is_empty() {
        sink(&chunk);
    }
    Ok(count)
}

/// One non-blank, non-comment line of an XYZ/CSV file: three numbers x y z
/// split by spaces, commas, tabs or semicolons (more fields are ignored).
/// `Ok(None)` for a line with no number when `header_allowed` (a header of
/// column names before the data); otherwise a short line or a coordinate
/// that is not finite is an error message.
pub(super) fn xyz_line(text: &str, header_allowed: bool) -> Result<Option<DVec3>, String> {
    let mut fields = text
        .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|f| !f.is_empty());
    let mut xyz = [0.0; 3];
    let mut parsed = 0;
    for slot in &mut xyz {
        match fields.next().map(str::parse::<f64>) {
            Some(Ok(v)) if v.is_finite() => {
                *slot = v;
                parsed += 1;
            }
            Some(Ok(v)) => return Err(format!("coordinate {v} is not finite")),
            _ => break,
        }
    }
    match parsed {
        3 => Ok(Some(DVec3::from(xyz))),
        0 if header_allowed => Ok(None),
        _ => Err(format!("expected three numbers x y z, found {text:?}")),
    }
}

/// A scalar PLY property type: its size in bytes and whether it is a float.
fn scalar(name: &str) -> Option<(usize, u8)> {
    // kind: 0 signed int, 1 unsigned int, 2 float
    Some(match name {
        "char" | "int8" => (1, 0),
        "uchar" | "uint8" => (1, 1),
        "short" | "int16" => (2, 0),
        "ushort" | "uint16" => (2, 1),
        "int" | "int32" => (4, 0),
        "uint" | "uint32" => (4, 1),
        "float" | "float32" => (4, 2),
        "double" | "float64" => (8, 2),
        _ => return None,
    })
}

fn decode(bytes: &[u8], size: usize, kind: u8, little: bool) -> f64 {
    let mut b = [0u8; 8];
    b[..size].copy_from_slice(bytes);
    if !little {
        b[..size].reverse();
    }
    match (size, kind) {
        (1, 0) => b[0] as i8 as f64,
        (1, _) => b[0] as f64,
        (2, 0) => i16::from_le_bytes([b[0], b[1]]) as f64,
        (2, _) => u16::from_le_bytes([b[0], b[1]]) as f64,
        (4, 0) => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
        (4, 1) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
        (4, _) => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
        _ => f64::from_le_bytes(b),
    }
}

fn read_ply(
    path: &Path,
    mut reader: impl BufRead,
    sink: &mut impl FnMut(&[DVec3]),
) -> Result<u64, ScanError> {
    let mut line_no = 0u64;
    let mut format = None;
    let mut vertices: Option<u64> = None;
    let mut in_vertex = false;
    // (offset, size, kind) of each vertex property; x, y, z indices.
    let mut props: Vec<(usize, u8)> = Vec::new();
    let mut xyz = [usize::MAX; 3];
    let mut header_bytes = 0u64;
    loop {
        let mut line = String::new();
        let n = reader
            .read_line(&mut line)
            .map_err(|e| ScanError::io(path, e))?;
        header_bytes += n as u64;
        line_no += 1;
        if n == 0 {
            return Err(bad(path, line_no, "end of file inside the PLY header"));
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["ply"] | [] => {}
            ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, _] => format = Some(f.to_string()),
            ["element", name, count] => {
                if vertices.is_some() {
                    in_vertex = false;
                    continue;
                }
                if *name != "vertex" {
                    return Err(bad(
                        path,
                        line_no,
                        format!("element {name:?} before \"vertex\": vertices must come first"),
                    ));
                }
                vertices = Some(count.parse().map_err(|_| {
                    bad(
                        path,
                        line_no,
                        format!("vertex count {count:?} is not a number"),
                    )
                })?);
                in_vertex = true;
            }
            ["property", "list", ..] if in_vertex => {
                return Err(bad(path, line_no, "list property in the vertex element"));
            }
            ["property", ty, name] if in_vertex => {
                let (size, kind) = scalar(ty)
                    .ok_or_else(|| bad(path, line_no, format!("unknown property type {ty:?}")))?;
                if let Some(k) = ["x", "y", "z"].iter().position(|a| a == name) {
                    xyz[k] = props.len();
                }
                props.push((size, kind));
            }
            ["property", ..] => {}
            ["end_header"] => break,
            _ => {
                return Err(bad(
                    path,
                    line_no,
                    format!("unexpected header line {:?}", line.trim()),
                ));
            }
        }
    }
    let count = vertices.ok_or_else(|| bad(path, line_no, "no vertex element"))?;
    if xyz.contains(&usize::MAX) {
        return Err(bad(path, line_no, "the vertex element lacks x, y or z"));
    }
    let mut chunk = Vec::with_capacity(CHUNK);
    let mut flush = |chunk: &mut Vec<DVec3>, force: bool| {
        if chunk.len() == CHUNK || (force && !chunk.is_empty()) {
            sink(chunk);
            chunk.clear();
        }
    };
    match format.as_deref() {
        Some("ascii") => {
            for i in 0..count {
                let mut line = String::new();
                let n = reader
                    .read_line(&mut line)
                    .map_err(|e| ScanError::io(path, e))?;
                let number = line_no + i + 1;
                if n == 0 {
                    return Err(bad(
                        path,
                        number,
                        format!("{i} of {count} vertices, then end of file"),
                    ));
                }
                let values: Vec<f64> = line
                    .split_whitespace()
                    .map(str::parse::<f64>)
                    .collect::<Result<_, _>>()
                    .map_err(|_| bad(path, number, format!("not numbers: {:?}", line.trim())))?;
                if values.len() < props.len() {
                    return Err(bad(
                        path,
                        number,
                        format!("{} values, {} properties", values.len(), props.len()),
                    ));
                }
                let p = DVec3::new(values[xyz[0]], values[xyz[1]], values[xyz[2]]);
                if !p.is_finite() {
                    return Err(bad(path, number, "coordinate not finite"));
                }
                chunk.push(p);
                flush(&mut chunk, false);
            }
        }
        Some(f @ ("binary_little_endian" | "binary_big_endian")) => {
            let little = f == "binary_little_endian";
            let mut offsets = Vec::with_capacity(props.len());
            let mut size = 0;
            for &(s, _) in &props {
                offsets.push(size);
                size += s;
            }
            let mut record = vec![0u8; size];
            for i in 0..count {
                reader.read_exact(&mut record).map_err(|_| {
                    bad(
                        path,
                        header_bytes + i * size as u64,
                        format!("{i} of {count} vertices, then end of file"),
                    )
                })?;
                let c = |k: usize| {
                    let (s, kind) = props[xyz[k]];
                    let o = offsets[xyz[k]];
                    decode(&record[o..o + s], s, kind, little)
                };
                let p = DVec3::new(c(0), c(1), c(2));
                if !p.is_finite() {
                    return Err(bad(
                        path,
                        header_bytes + i * size as u64,
                        "coordinate not finite",
                    ));
                }
                chunk.push(p);
                flush(&mut chunk, false);
            }
        }
        other => {
            return Err(bad(path, 2, format!("unknown PLY format {other:?}")));
        }
    }
    flush(&mut chunk, true);
    Ok(count)
}
