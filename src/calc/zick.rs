//! Stresses in a horizontal vessel on two saddles by L. P. Zick's method ("Stresses
//! in Large Horizontal Cylindrical Pressure Vessels on Two Saddle Supports", The
//! Welding Journal Research Supplement, September 1951; revised 1971), in the
//! form of Moss, *Pressure Vessel Design Manual*, Procedure 3-9, and Megyesy,
//! *Pressure Vessel Handbook*, "Stresses in large horizontal vessels supported by
//! two saddles".
//!
//! One saddle of load `Q` (N) at distance `A` from the nearer tangent line of a
//! shell of mean radius `R`, wall `ts`, tangent length `L`, head depth `H`, saddle
//! width `b` and contact angle θ:
//!
//! - S1, longitudinal bending: at the saddle M1 = Q·A·[1 − (1 − A/L + (R² − H²)/(2AL))
//!   / (1 + 4H/(3L))] over the section K1·π·R²·ts (K1 at the top, tension; K1* at
//!   the bottom, compression; both 1 when the shell is stiffened by the head,
//!   A ≤ R/2); at midspan M2 = Q·L/4·[(1 + 2(R² − H²)/L²)/(1 + 4H/(3L)) − 4A/L]
//!   over π·R²·ts.
//! - S2, tangential shear: A > R/2, K2·Q/(R·ts)·(L − 2A)/(L + 4H/3); A ≤ R/2, K3·Q/(R·ts)
//!   in the shell and K3·Q/(R·th) in the head, with the head's additional
//!   membrane stress K4·Q/(R·th).
//! - S3, circumferential at the horn: −Q/(4·t·(b + 1.56√(R·ts))) − 3·K6·Q/(2·t²)
//!   when L ≥ 8R, else −Q/(4·t·(b + 1.56√(R·ts))) − 12·K6·Q·R/(L·t²); K6 in full
//!   for A/R ≥ 1, a quarter of it for A/R ≤ 0.5, linear between.
//! - S4, circumferential compression at the bottom of the shell:
//!   −K5·Q/(t·(b + 1.56√(R·ts))).
//!
//! In S3 and S4 `t` is the shell wall, or the shell plus a wear plate that reaches
//! at least R/10 above the horn (Zick's condition for counting it; Megyesy's rule).
//!
//! The factors are Zick's closed forms in the contact angle (β = π − θ/2,
//! α = 0.95·β, Δ = π/6 + 5θ/12), not values read off his table; at θ = 120° they give
//! his table's K1 = 0.107 (Megyesy's π·K1 = 0.335), K2 = 1.171, K3 = 0.880,
//! K4 = 0.401, K5 = 0.760, K6 = 0.053 (tested).
//! The same closed forms are ASME VIII-2 Table 4.15.1's (K1, K1*, K2–K6); checked
//! against a public Python implementation of Div 2 §4.15, they agree to 1e-16
//! at every contact angle from 120° to 180°.

use std::f64::consts::PI;

use serde::Serialize;

/// Zick's factors for one contact angle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Factors {
    /// Effective fraction of the section at the saddle, top (tension), K1.
    pub k1: f64,
    /// The same at the bottom (compression), K1*.
    pub k1_bottom: f64,
    /// Tangential shear, saddle away from the head (A > R/2), K2.
    pub k2: f64,
    /// Tangential shear, saddle near the head (A ≤ R/2), K3.
    pub k3: f64,
    /// Additional membrane stress in the head (A ≤ R/2), K4.
    pub k4: f64,
    /// Circumferential compression at the bottom, K5.
    pub k5: f64,
    /// Circumferential bending at the horn for A/R ≥ 1, K6.
    pub k6: f64,
}

/// Zick's factors for contact angle `theta` degrees (120–180 in practice).
pub fn factors(theta: f64) -> Factors {
    let t = theta.to_radians();
    let beta = PI - t / 2.0;
    let alpha = 0.95 * beta;
    let delta = PI / 6.0 + 5.0 * t / 12.0;
    let (sa, ca) = alpha.sin_cos();
    let den = PI - alpha + sa * ca;
    let (sd, cd) = delta.sin_cos();
    let n = delta + sd * cd - 2.0 * sd * sd / delta;
    let (sb, cb) = beta.sin_cos();
    let q = (sb / beta).powi(2) - 0.5 - (2.0 * beta).sin() / (4.0 * beta);
    let k6_num = 0.75 * cb * (sb / beta).powi(2) - 5.0 * sb * cb * cb / (4.0 * beta)
        + cb.powi(3) / 2.0
        - sb / (4.0 * beta)
        + cb / 4.0
        - beta * sb * q;
    Factors {
        k1: n / (PI * (sd / delta - cd)),
        k1_bottom: n / (PI * (1.0 - sd / delta)),
        k2: sa / den,
        k3: sa / PI * (alpha - sa * ca) / den,
        k4: 0.375 * sa * sa / den,
        k5: (1.0 + ca) / den,
        k6: k6_num / (2.0 * PI * q),
    }
}

/// The inputs of one saddle (N, mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Saddle {
    /// Load on the saddle, N.
    pub load: f64,
    /// Distance from the saddle centre to the nearer tangent line, mm.
    pub a: f64,
    /// Tangent-to-tangent length, mm.
    pub l: f64,
    /// Mean radius of the shell, mm.
    pub r: f64,
    /// Shell wall, mm.
    pub ts: f64,
    /// Wall of the nearer head, mm.
    pub th: f64,
    /// Depth of the head, mm (the nearer head for the saddle, the shallower for
    /// midspan).
    pub h: f64,
    /// Saddle width along the axis, mm.
    pub b: f64,
    /// Contact angle, degrees.
    pub theta: f64,
    /// Wear plate counted in S3 and S4 (reaching R/10 above the horn), mm; 0 for none.
    pub wear_plate: f64,
}

/// Zick's stresses at one saddle, MPa (bending: tension positive).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stresses {
    /// Whether the head stiffens the shell at the saddle (A ≤ R/2).
    pub stiffened: bool,
    /// Bending moment at the saddle, N·mm (negative: hogging).
    pub m_saddle: f64,
    /// Bending moment at midspan, N·mm (positive: sagging).
    pub m_midspan: f64,
    /// S1 at the saddle, top of the shell (tension when hogging), MPa.
    pub s1_saddle_top: f64,
    /// S1 at the saddle, bottom of the shell, MPa.
    pub s1_saddle_bottom: f64,
    /// S1 at midspan, bottom (tension when sagging; the top is its negative), MPa.
    pub s1_midspan: f64,
    /// S2, tangential shear in the shell, MPa.
    pub s2_shell: f64,
    /// S2 in the head (A ≤ R/2 only), MPa.
    pub s2_head: Option<f64>,
    /// Additional membrane stress in the head (A ≤ R/2 only), MPa.
    pub head_additional: Option<f64>,
    /// S3, circumferential stress at the horn (compression negative), MPa.
    pub s3_horn: f64,
    /// S4, circumferential compression at the bottom of the shell, MPa.
    pub s4_bottom: f64,
    /// The factors used.
    pub factors: Factors,
    /// K6 after its reduction for A/R < 1.
    pub k6_used: f64,
}

/// Zick's stresses of `s`; an error for inputs outside the method (not positive,
/// the saddle beyond midspan).
pub fn stresses(s: &Saddle) -> Result<Stresses, String> {
    for (name, v) in [
        ("Q", s.load),
        ("L", s.l),
        ("R", s.r),
        ("ts", s.ts),
        ("th", s.th),
        ("b", s.b),
        ("theta", s.theta),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(format!("Zick: {name} = {v} must be finite and > 0"));
        }
    }
    if !(s.a.is_finite() && s.a >= 0.0 && s.a < s.l / 2.0) {
        return Err(format!(
            "Zick: A = {} mm must lie between the tangent line and midspan (L/2 = {} mm)",
            s.a,
            s.l / 2.0
        ));
    }
    if !(s.h.is_finite() && s.h >= 0.0 && s.wear_plate.is_finite() && s.wear_plate >= 0.0) {
        return Err(format!(
            "Zick: H = {} mm and wear plate {} mm must be finite and >= 0",
            s.h, s.wear_plate
        ));
    }
    let f = factors(s.theta);
    let (q, a, l, r, ts, h) = (s.load, s.a, s.l, s.r, s.ts, s.h);
    let stiffened = a <= r / 2.0;
    let lever = 1.0 + 4.0 * h / (3.0 * l);
    let m_saddle = if a > 0.0 {
        -q * a * (1.0 - (1.0 - a / l + (r * r - h * h) / (2.0 * a * l)) / lever)
    } else {
        0.0
    };
    let m_midspan = q * l / 4.0 * ((1.0 + 2.0 * (r * r - h * h) / (l * l)) / lever - 4.0 * a / l);
    let section = PI * r * r * ts;
    let (k1, k1b) = if stiffened {
        (1.0, 1.0)
    } else {
        (f.k1, f.k1_bottom)
    };
    let (s2_shell, s2_head, head_additional) = if stiffened {
        (
            f.k3 * q / (r * ts),
            Some(f.k3 * q / (r * s.th)),
            Some(f.k4 * q / (r * s.th)),
        )
    } else {
        (
            f.k2 * q / (r * ts) * (l - 2.0 * a) / (l + 4.0 * h / 3.0),
            None,
            None,
        )
    };
    let ratio = a / r;
    let k6_used = f.k6
        * if ratio >= 1.0 {
            1.0
        } else if ratio <= 0.5 {
            0.25
        } else {
            0.25 + 0.75 * (ratio - 0.5) / 0.5
        };
    let t = ts + s.wear_plate;
    let band = s.b + 1.56 * (r * ts).sqrt();
    let direct = -q / (4.0 * t * band);
    let s3_horn = if l >= 8.0 * r {
        direct - 3.0 * k6_used * q / (2.0 * t * t)
    } else {
        direct - 12.0 * k6_used * q * r / (l * t * t)
    };
    Ok(Stresses {
        stiffened,
        m_saddle,
        m_midspan,
        // Hogging (M1 < 0) puts the top in tension.
        s1_saddle_top: -m_saddle / (k1 * section),
        s1_saddle_bottom: m_saddle / (k1b * section),
        s1_midspan: m_midspan / section,
        s2_shell,
        s2_head,
        head_additional,
        s3_horn,
        s4_bottom: -f.k5 * q / (t * band),
        factors: f,
        k6_used,
    })
}
