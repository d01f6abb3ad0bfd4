//! ASPRS LAS and LAZ (compressed LAS) point files through the `las` crate,
//! streamed: the reader decodes the caller's chunk of points at a time into one reused
//! buffer and hands their coordinates to the callback, so a scan of millions
//! of points is never held twice.
//!
//! Coordinates are taken as they are (scale and offset applied), in mm like
//! every other point file. The writer stores them as 32-bit integers of
//! 0.001 mm about an offset at the centre of the points' box (coarser when the
//! box is wider than ±2 km), point format 0, LAS 1.2; `.laz` compresses.

use std::path::Path;

use glam::DVec3;
use las::{Builder, Point, PointDataBuilder, Reader, Transform, Vector, Writer};

use super::ScanError;
use super::error::bad;

/// The first four bytes of every LAS and LAZ file.
pub const MAGIC: &[u8; 4] = b"LASF";

/// The finest step stored, mm.
const STEP: f64 = 0.001;

/// A `las` crate error as a [`ScanError`] naming the file (no line: LAS is
/// binary, and the crate does not say where).
fn las_error(path: &Path, what: &str, e: las::Error) -> ScanError {
    match e {
        las::Error::Io(source) => ScanError::io(path, source),
        other => bad(path, 0, format!("{what}: {other}")),
    }
}

/// Reads the points of the LAS or LAZ file `path`, handing them to `sink` in
/// chunks of at most `chunk_len`. Returns the number of points read.
///
/// # Errors
///
/// [`ScanError::Io`] when the file cannot be read, [`ScanError::Points`] when
/// its header or records are malformed or a coordinate is not finite.
pub fn read_las(
    path: &Path,
    chunk_len: usize,
    sink: &mut impl FnMut(&[DVec3]),
) -> Result<u64, ScanError> {
    let mut reader = Reader::from_path(path).map_err(|e| las_error(path, "LAS header", e))?;
    let total = reader.header().number_of_points();
    let mut data = PointDataBuilder::new().for_header(reader.header()).build();
    let mut chunk = Vec::with_capacity(chunk_len);
    let mut count = 0u64;
    loop {
        let n = reader
            .fill_points(chunk_len as u64, &mut data)
            .map_err(|e| las_error(path, &format!("point {count} of {total}"), e))?;
        if n == 0 {
            break;
        }
        chunk.clear();
        chunk.extend(
            data.x()
                .zip(data.y())
                .zip(data.z())
                .map(|((x, y), z)| DVec3::new(x, y, z)),
        );
        if let Some(k) = chunk.iter().position(|p| !p.is_finite()) {
            return Err(bad(
                path,
                0,
                format!("point {}: coordinate not finite", count + k as u64),
            ));
        }
        count += n;
        sink(&chunk);
    }
    if count != total {
        return Err(bad(
            path,
            0,
            format!("the header counts {total} points, the file holds {count}"),
        ));
    }
    Ok(count)
}

/// Writes `points` to `path` as LAS, or as LAZ when `compressed`.
///
/// # Errors
///
/// [`ScanError::Io`] when the file cannot be written, [`ScanError::Points`]
/// when the crate refuses a point (a coordinate not finite).
pub fn write_las(path: &Path, points: &[DVec3], compressed: bool) -> Result<(), ScanError> {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let axis = |lo: f64, hi: f64| {
        if !(lo.is_finite() && hi.is_finite()) {
            return Transform {
                scale: STEP,
                offset: 0.0,
            };
        }
        // ±2e9 steps either side of a whole-mm centre.
        let offset = (0.5 * (lo + hi)).round();
        let reach = (hi - offset).max(offset - lo);
        let mut scale = STEP;
        while reach / scale > 2.0e9 {
            scale *= 10.0;
        }
        Transform { scale, offset }
    };
    let mut builder = Builder::from((1, 2));
    builder.generating_software = "vesselcad scan".to_string();
    builder.point_format.is_compressed = compressed;
    builder.transforms = Vector {
        x: axis(lo.x, hi.x),
        y: axis(lo.y, hi.y),
        z: axis(lo.z, hi.z),
    };
    let header = builder
        .into_header()
        .map_err(|e| las_error(path, "LAS header", e))?;
    let file = std::fs::File::create(path).map_err(|e| ScanError::io(path, e))?;
    let mut writer = Writer::new(std::io::BufWriter::new(file), header)
        .map_err(|e| las_error(path, "LAS header", e))?;
    for (i, p) in points.iter().enumerate() {
        writer
            .write_point(Point {
                x: p.x,
                y: p.y,
                z: p.z,
                ..Point::default()
            })
            .map_err(|e| las_error(path, &format!("point {i}"), e))?;
    }
    writer
        .close()
        .map_err(|e| las_error(path, "closing the file", e))
}
