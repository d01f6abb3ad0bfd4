//! Weld-metal cross-sections of the preparations in the shop rules, so a weld's
//! metal volume is its cross-section times its length. Stated geometry, no
//! reinforcement or root bead excess (add a margin in the rules' angles or gaps):
//!
//! - double-V of included angle α, gap g, root face f through thickness t:
//!   g·t + 2·h²·tan(α/2) with h = (t − f)/2;
//! - single-V: g·t + h²·tan(α/2) with h = t − f;
//! - single bevel of angle β (set-in branch through the host's wall t) with a
//!   cover fillet of leg c: g·t + (t − f)²·tan β / 2 + c²/2;
//! - fillet of throat a = ratio · t (t the thinner part): a right isosceles
//!   triangle of leg a·√2, area a².

use super::shop_rules::{Prep, PrepKind};

/// Weld-metal cross-section of `prep` through thickness `t` mm, mm².
pub fn cross_section(prep: &Prep, t: f64) -> f64 {
    let t = t.max(0.0);
    let g = prep.root_gap;
    let f = prep.root_face.min(t);
    let half = (prep.included_angle / 2.0).to_radians().tan();
    match prep.kind {
        PrepKind::DoubleV => {
            let h = (t - f) / 2.0;
            g * t + 2.0 * h * h * half
        }
        PrepKind::SingleV => {
            let h = t - f;
            g * t + h * h * half
        }
        PrepKind::SingleBevel => {
            let h = t - f;
            let c = prep.cover_fillet;
            g * t + h * h * prep.included_angle.to_radians().tan() / 2.0 + c * c / 2.0
        }
        PrepKind::Fillet => {
            let a = prep.throat_ratio * t;
            a * a
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn prep(kind: PrepKind, angle: f64) -> Prep {
        Prep {
            id: "X".into(),
            joint: "x".into(),
            kind,
            included_angle: angle,
            root_gap: 2.0,
            root_face: 2.0,
            cover_fillet: 6.0,
            throat_ratio: 0.5,
            note: String::new(),
        }
    }

    #[test]
    fn cross_sections_by_hand() {
        // 20 mm double-V 60°: 2·20 + 2·9²·tan 30° = 40 + 93.53.
        let dv = cross_section(&prep(PrepKind::DoubleV, 60.0), 20.0);
        assert!((dv - (40.0 + 162.0 / 3f64.sqrt())).abs() < 1e-9, "{dv}");
        // 12 mm single-V 60°: 24 + 10²·tan 30°.
        let sv = cross_section(&prep(PrepKind::SingleV, 60.0), 12.0);
        assert!((sv - (24.0 + 100.0 / 3f64.sqrt())).abs() < 1e-9, "{sv}");
        // 12 mm single bevel 45°: 24 + 10²/2 + 6²/2.
        let sb = cross_section(&prep(PrepKind::SingleBevel, 45.0), 12.0);
        assert!((sb - (24.0 + 50.0 + 18.0)).abs() < 1e-9, "{sb}");
        // Fillet, throat 6 mm on 12 mm: 36 mm².
        let fw = cross_section(&prep(PrepKind::Fillet, 0.0), 12.0);
        assert!((fw - 36.0).abs() < 1e-12, "{fw}");
    }
}
