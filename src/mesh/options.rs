//! Tessellation options: the chordal tolerance and optional angle and edge-length
//! limits that drive meshing.

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
}

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
}

impl TessellationOptions {
    /// 0.5 mm chordal tolerance, 15° angle tolerance, no edge or stretch limit.
    pub const DEFAULT: TessellationOptions = TessellationOptions {
        tolerance: 0.5,
        angle_tolerance: Some(15.0),
        max_edge_length: None,
        max_stretch: None,
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

    /// Checks every option.
    pub fn validate(&self) -> Result<(), OptionsError> {
        let bad = |field, value, rule| Err(OptionsError::Invalid { field, value, rule });
        if !(self.tolerance.is_finite() && self.tolerance >= 1e-6 && self.tolerance <= 1e4) {
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
        match options.validate() {
            Ok(()) => None,
            Err(OptionsError::Invalid { field, .. }) => Some(field),
        }
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
    }
}
