//! Typical supports and boot for a 2400 mm course: the fixtures the support tests
//! start from before bending one number.

use vesselcad::parts::{Boot, Legs, Lugs, Saddle, Skirt};

/// Outside diameter of the course the supports fit, mm.
pub const OD: f64 = 2400.0;

/// A skirt under the course with the given flare (degrees) and base ring width.
pub fn skirt_with(flare_angle: f64, base_ring_width: f64) -> Skirt {
    Skirt {
        top_diameter: OD,
        height: 3000.0,
        flare_angle,
        thickness: 12.0,
        base_ring_width,
    }
}

/// A 120° saddle.
pub fn saddle() -> Saddle {
    Saddle {
        shell_diameter: OD,
        contact_angle: 120.0,
        width: 300.0,
        height: 1600.0,
        web_thickness: 12.0,
        base_length: 2400.0,
        base_width: 250.0,
        base_thickness: 20.0,
    }
}

/// Four pipe legs.
pub fn legs() -> Legs {
    Legs {
        count: 4,
        pipe_diameter: 219.1,
        length: 1800.0,
        shell_diameter: OD,
        first_angle: 45.0,
    }
}

/// Four lugs.
pub fn lugs() -> Lugs {
    Lugs {
        count: 4,
        shell_diameter: OD,
        height: 400.0,
        projection: 300.0,
        width: 250.0,
        first_angle: 0.0,
    }
}

/// A 600 × 900 boot.
pub fn boot() -> Boot {
    Boot::new(600.0, 900.0, OD)
}
