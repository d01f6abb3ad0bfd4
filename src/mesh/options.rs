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
    /// 0.5 mm chordal tolerance, 15° angle tolerance, no edge limit.
    pub const DEFAULT: TessellationOptions = TessellationOptions {
        tolerance: 0.5,
        angle_tolerance: Some(15.0),
        max_edge_length: None,
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
        Ok(())
    }
}

impl Default for TessellationOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
