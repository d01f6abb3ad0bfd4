//! One nozzle's developed cuts: the opening in its host plate, the pad's
//! footprint and developed outline, the neck's saddle end. The leaf that
//! the course openings ([`super::openings`]) and the cone openings
//! ([`super::cone_openings`]) both produce and the seams, plates, nesting
//! and drawings read.

use glam::DVec2;

use super::neck_axis::{NeckAxis, SurfaceLoop};

/// A reinforcing pad developed as the region of the shell it covers.
#[derive(Clone, Debug, PartialEq)]
pub struct PadPiece {
    /// Pad outside diameter, mm.
    pub od: f64,
    /// Thickness, mm.
    pub thickness: f64,
    /// Its footprint on the shell's outside, surface coordinates.
    pub footprint: SurfaceLoop,
    /// Developed outline on the pad's mid-surface, centred on the nozzle
    /// axis, mm.
    pub outline: Vec<DVec2>,
    /// Developed hole for the neck, same frame, mm.
    pub hole: Vec<DVec2>,
    /// On a cone, the developed apex of the pad's own cone in the same
    /// frame: the pad is rolled as a cone about it. `None` on a course (the
    /// pad is rolled as a cylinder).
    pub apex: Option<DVec2>,
}

impl PadPiece {
    /// Developed area (outline less hole, polygon areas), mm².
    pub fn area(&self) -> f64 {
        polygon_area(&self.outline).abs() - polygon_area(&self.hole).abs()
    }
}

/// One nozzle's (or boot's) cuts on a cylindrical course, or a nozzle's on a
/// cone (then `(θ, z)` are on the cone's mid-surface, θ about the centre of
/// the circle at `z` on an eccentric reducer, and the pad is developed on its
/// own cone: [`super::cone_openings`]).
#[derive(Clone, Debug, PartialEq)]
pub struct NozzleCut {
    /// Index of the nozzle in the resolved vessel (a boot's: of its part).
    pub nozzle: usize,
    /// Mark (a boot's: its part id).
    pub mark: String,
    /// JSON path, `vessels[0].nozzles[3]` (a boot's `vessels[0].parts[5]`).
    pub path: String,
    /// Index in [`Developments::rolled`](super::develop::Developments::rolled) of its course or cone.
    pub rolled: usize,
    /// The axis in the course's frame.
    pub neck: NeckAxis,
    /// Radius of the cutting cylinder, mm.
    pub cut_radius: f64,
    /// Where the axis meets the course's mid-surface, `(θ, z)`.
    pub centre: DVec2,
    /// The opening on the course's mid-surface.
    pub hole: SurfaceLoop,
    /// The pad, if any.
    pub pad: Option<PadPiece>,
    /// The neck's end developed on its mid-surface: `(r·φ, length from the
    /// cut to the flange's back)`, φ from 0 to 360° inclusive (a boot's:
    /// to its head's tangent line).
    pub saddle: Vec<DVec2>,
}

/// A neck's end developed on its mid-surface radius `neck_mid` from `n + 1`
/// angles φ round it: `(neck_mid·φ, back − s(φ))`, where `s(φ)` is how far
/// along the neck its line at φ meets the host; `None` if one line misses.
pub fn saddle(
    n: usize,
    neck_mid: f64,
    back: f64,
    s: impl Fn(f64) -> Option<f64>,
) -> Option<Vec<DVec2>> {
    (0..=n)
        .map(|i| {
            let phi = std::f64::consts::TAU * i as f64 / n as f64;
            s(phi).map(|s| DVec2::new(neck_mid * phi, back - s))
        })
        .collect()
}

/// Signed area of a closed polygon (shoelace), mm².
pub fn polygon_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum::<f64>()
        * 0.5
}
