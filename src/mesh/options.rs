//! Tessellation options: the chordal tolerance and optional angle and edge-length
//! limits that drive meshing, and the vertex budget that bounds its work.

use thiserror::Error;

/// Options of the mesher.
///
/// `tolerance` is the chordal tolerance: the largest distance, in mm, allowed
/// between the exact surface and its triangle approximation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TessellationOptions {
    /// Chordal tolerance, mm (> 0).
    pub tolerance: f64,
    /// Largest angle, degrees, between the normals at the ends of an edge; `None`
    /// for no limit.
    pub angle_tolerance: Option<f64>,
    /// Longest edge allowed, mm; `None` for no limit.
    pub max_edge_length: Option<f64>,
    /// Largest ratio (≥ 1) between a patch's target edge lengths in two directions
    /// at one point; `None` (the default) for no limit. Curvature alone sizes a
    /// cylinder's straight generators at the whole course length, which gives the
    /// fewest triangles but strips of needles; a stretch of 3 keeps the smallest
    /// angle of a metric-equilateral triangle above about 19° (for analysis meshes)
    /// at the cost of rows on cylinders and cones. The seam sides of a closed patch
    /// (which belong to it alone) are then sampled with the same cap relative to the
    /// spacing along its other sides.
    pub max_stretch: Option<f64>,
    /// Most vertices one patch region may get (seeds, loop vertices and
    /// insertions), from [`MIN_VERTEX_BUDGET`] to [`MAX_VERTEX_BUDGET`]. A patch
    /// that needs more is refused with
    /// [`CdtError::BudgetExceeded`](crate::mesh::cdt::CdtError::BudgetExceeded)
    /// as soon as the seeding estimate or the refinement passes it, so the work
    /// of one patch is bounded by it (memory and time grow with it linearly).
    pub max_vertices: usize,
}

/// The extent, mm, the storage budget is taken for at least: parts up to 32 m
/// (every part of the example designs and of generated plants) share one budget,
/// so a vessel drawn or exported alone is meshed as it is in its plant.
pub const STORAGE_FLOOR_EXTENT: f64 = 16_000.0;

/// The default [`TessellationOptions::max_vertices`]: 4 000 000 vertices, about
/// 0.5 GB of mesher state for one patch.
pub const DEFAULT_VERTEX_BUDGET: usize = 4_000_000;

/// The smallest [`TessellationOptions::max_vertices`]: below it a patch with a
/// few openings cannot even hold its loop vertices and seed rows.
pub const MIN_VERTEX_BUDGET: usize = 1_000;

/// The largest [`TessellationOptions::max_vertices`]: meshes index their
/// vertices with `u32`.
pub const MAX_VERTEX_BUDGET: usize = u32::MAX as usize;

/// A rejected tessellation option.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum OptionsError {
    /// An option is NaN, infinite, zero or negative, or out of its range.
    #[error("tessellation option {field} = {value}: {rule}")]
    Invalid {
        /// The option.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The rule.
        rule: &'static str,
    },
    /// The tolerance is finer than `f32` storage lets the mesher work to: glTF
    /// stores `f32` metres, whose rounding is budgeted inside the tolerance
    /// (see [`storage_options`](crate::mesh::storage_options)); when it takes
    /// half the tolerance or more the patches are meshed to half the tolerance,
    /// which here falls below the mesher's `MIN_TOLERANCE` (1e-6 mm).
    #[error(
        "tessellation option tolerance = {tolerance} mm is finer than f32 storage allows{}: \
         glTF's f32 metres round a point by up to {rounding:.3e} mm at that size, so the \
         patches would be meshed to {meshed:e} mm, below the mesher's {MIN_TOLERANCE:e} mm \
         floor; the smallest tolerance is {smallest:e} mm",
        match extent {
            Some(e) => format!(
                " for this design (its largest part reaches {e:.0} mm; storage is \
                 budgeted for at least {:.0} mm)",
                STORAGE_FLOOR_EXTENT
            ),
            None => format!(
                " for any design (storage is budgeted for parts of at least {:.0} mm)",
                STORAGE_FLOOR_EXTENT
            ),
        }
    )]
    BelowStorageFloor {
        /// The tolerance asked for, mm.
        tolerance: f64,
        /// The largest coordinate of any part of the design in its part's
        /// frame, mm, when the design is known.
        extent: Option<f64>,
        /// The `f32` rounding bound budgeted, mm.
        rounding: f64,
        /// The tolerance the patches would be meshed to, mm.
        meshed: f64,
        /// The smallest tolerance the design can be meshed and stored to, mm.
        smallest: f64,
    },
}

impl OptionsError {
    /// The option at fault (`tolerance`, `max_vertices`, …): the command line
    /// names its flag after it (`--max-vertices`).
    pub fn field(&self) -> &'static str {
        match self {
            OptionsError::Invalid { field, .. } => field,
            OptionsError::BelowStorageFloor { .. } => "tolerance",
        }
    }

    /// The value of the option at fault.
    pub fn value(&self) -> f64 {
        match *self {
            OptionsError::Invalid { value, .. } => value,
            OptionsError::BelowStorageFloor { tolerance, .. } => tolerance,
        }
    }
}

/// The finest chordal tolerance the mesher takes, mm.
pub const MIN_TOLERANCE: f64 = 1e-6;

impl TessellationOptions {
    /// 0.5 mm chordal tolerance, 15° angle tolerance, no edge or stretch limit,
    /// [`DEFAULT_VERTEX_BUDGET`] vertices per patch.
    pub const DEFAULT: TessellationOptions = TessellationOptions {
        tolerance: 0.5,
        angle_tolerance: Some(15.0),
        max_edge_length: None,
        max_stretch: None,
        max_vertices: DEFAULT_VERTEX_BUDGET,
    };

    /// The default options with chordal tolerance `tolerance` mm.
    pub fn chord(tolerance: f64) -> Self {
        Self {
            tolerance,
            ..Self::DEFAULT
        }
    }

    /// With an angle tolerance in degrees (`None` for no limit).
    pub fn with_angle_tolerance(mut self, degrees: Option<f64>) -> Self {
        self.angle_tolerance = degrees;
        self
    }

    /// With a maximum stretch (`None` for no limit).
    pub fn with_max_stretch(mut self, stretch: Option<f64>) -> Self {
        self.max_stretch = stretch;
        self
    }

    /// With a maximum edge length in mm (`None` for no limit).
    pub fn with_max_edge_length(mut self, length: Option<f64>) -> Self {
        self.max_edge_length = length;
        self
    }

    /// With a vertex budget per patch.
    pub fn with_max_vertices(mut self, vertices: usize) -> Self {
        self.max_vertices = vertices;
        self
    }

    /// Checks every option.
    pub fn validate(&self) -> Result<(), OptionsError> {
        let bad = |field, value, rule| Err(OptionsError::Invalid { field, value, rule });
        if !(self.tolerance.is_finite() && self.tolerance >= MIN_TOLERANCE && self.tolerance <= 1e4)
        {
            return bad(
                "tolerance",
                self.tolerance,
                "must be a finite number from 1e-6 to 1e4 mm",
            );
        }
        if let Some(a) = self.angle_tolerance
            && !(a.is_finite() && a > 0.0 && a <= 90.0)
        {
            return bad(
                "angle_tolerance",
                a,
                "must be a finite angle in (0, 90] degrees",
            );
        }
        if let Some(l) = self.max_edge_length
            && !(l.is_finite() && l > 0.0)
        {
            return bad("max_edge_length", l, "must be a finite number > 0 mm");
        }
        if let Some(r) = self.max_stretch
            && !(r.is_finite() && r >= 1.0)
        {
            return bad("max_stretch", r, "must be a finite ratio >= 1");
        }
        if !(MIN_VERTEX_BUDGET..=MAX_VERTEX_BUDGET).contains(&self.max_vertices) {
            return bad(
                "max_vertices",
                self.max_vertices as f64,
                "must be a whole number of vertices from 1000 to 4294967295",
            );
        }
        Ok(())
    }
}

impl Default for TessellationOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The field a rejected option names.
    fn field(options: TessellationOptions) -> Option<&'static str> {
        options.validate().err().map(|e| e.field())
    }

    #[test]
    fn bad_values_name_their_field() {
        let d = TessellationOptions::DEFAULT;
        assert_eq!(field(d), None);
        for t in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(field(TessellationOptions::chord(t)), Some("tolerance"));
        }
        for a in [0.0, -5.0, 91.0, f64::NAN] {
            assert_eq!(
                field(d.with_angle_tolerance(Some(a))),
                Some("angle_tolerance")
            );
        }
        for l in [0.0, -1.0, f64::NAN] {
            assert_eq!(
                field(d.with_max_edge_length(Some(l))),
                Some("max_edge_length")
            );
        }
        for r in [0.5, 0.0, -2.0, f64::NAN, f64::INFINITY] {
            assert_eq!(field(d.with_max_stretch(Some(r))), Some("max_stretch"));
        }
        assert_eq!(field(d.with_max_stretch(Some(1.0))), None);
        for n in [0, 1, MIN_VERTEX_BUDGET - 1, MAX_VERTEX_BUDGET + 1] {
            assert_eq!(field(d.with_max_vertices(n)), Some("max_vertices"));
        }
        for n in [MIN_VERTEX_BUDGET, DEFAULT_VERTEX_BUDGET, MAX_VERTEX_BUDGET] {
            assert_eq!(field(d.with_max_vertices(n)), None);
        }
    }
}
