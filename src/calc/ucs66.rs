//! The two curves ASME VIII-1's impact-test exemption rests on, as functions:
//! Fig. UCS-66 (the coldest metal temperature a Part UCS material of curve A, B,
//! C or D needs no impact test at, against its governing thickness) and Fig.
//! UCS-66.1 (how much colder that temperature may go when the part is stressed
//! below its allowable: the reduction against the coincident ratio Rts). Both in
//! the Code's units, inches and °F; [`super::mdmt`] applies them to a part.
//!
//! Curves A, B and C are the closed forms ASME gives for the figure (a rational
//! function for A, series in √t for B and in 1/t for C), flat at 18, −20 and
//! −55 °F up to the Charpy specimen thickness 0.394 in and valid to 6 in. No
//! public copy of the equations' text was found to ship with them: each is
//! checked instead, at all 49 thicknesses from 0.25 to 3.3125 in by 1/16 in,
//! against the tabular values of Table UCS-66 as API RP 581 reproduces them for
//! its brittle-fracture screening (its Tref table, °F to 0.1, in a public Python
//! RBI code on GitHub, class `Table213`), every one within that table's rounding
//! (0.05 °F). Curve D is that table itself: −55 °F to 0.5 in, the published
//! values by 1/16 in to 3.3125 in (84.1 mm), linear between them; above, curve
//! D is refused (its closed form was not recovered to the table's precision).
//!
//! Fig. UCS-66.1: no reduction at Rts ≥ 1; 100 (1 − Rts) °F above Rts = 0.6; the
//! closed form ASME gives for the curve below, −9979.57 − 14125.0 Rts^1.5 +
//! 9088.11 e^Rts − 17.3893 ln(Rts)/Rts², from 0.6 down to 0.35 (it meets the line
//! at 0.6 within 0.01 °F); at 0.35 and below UCS-66(b)(3) takes over (no test
//! down to −155 °F). Here too no public copy of the equation's text was found;
//! it is checked against the reductions printed by published calculations: PV
//! Elite 2017 for Pressure Vessel Engineering Ltd.'s 2015-Code firetube boiler
//! and PV Elite 2012 for its heat exchanger sample (Rts 0.957, 0.941, 0.911,
//! 0.910, 0.699, 0.597, 0.379 → 4, 6, 9, 9, 30, 41, 118 °F) and COMPRESS for Key
//! Design Engineering's filter KEY-026 (Rts 0.38091 → 116.1 °F), every one within
//! 1 °F. One published point is off by more: PV Elite 2017's 2:1 head at Rts 0.574
//! prints 45 °F where this curve gives 41.7 °F, unexplained; the curve here is
//! the smaller reduction there, so the warmer (safe) MDMT.

/// The Charpy specimen thickness where curves A, B and C leave their flat
/// segment, in.
pub const CHARPY_THICKNESS_IN: f64 = 0.394;

/// The thickness Fig. UCS-66's curves end at, in (152.4 mm).
pub const CURVES_END_IN: f64 = 6.0;

/// Curve D as published by 1/16 in from 0.5 in (index 0) to 3.3125 in, °F.
const CURVE_D: [f64; 46] = [
    -55.0, -51.0, -47.5, -44.2, -41.1, -38.1, -35.3, -32.7, -30.1, -27.8, -25.5, -23.4, -21.4,
    -19.5, -17.6, -15.9, -14.3, -12.7, -11.2, -9.8, -8.5, -7.2, -5.9, -4.7, -3.6, -2.5, -1.4, -0.4,
    0.6, 1.6, 2.5, 3.4, 4.3, 5.2, 6.0, 6.9, 7.7, 8.5, 9.3, 10.1, 10.9, 11.7, 12.4, 13.2, 13.9,
    14.7,
];

/// Where the shipped curve D ends, in (84.1 mm).
pub const CURVE_D_END_IN: f64 = 0.5 + (CURVE_D.len() - 1) as f64 / 16.0;

/// The Fig. UCS-66 exemption temperature of curve `letter` at governing
/// thickness `t` in, °F; an error naming the figure for a letter other than
/// A–D or a thickness outside the curve's shipped range.
pub fn curve_f(letter: &str, t: f64) -> Result<f64, String> {
    if !(t.is_finite() && t > 0.0) {
        return Err(format!("governing thickness {t} in must be finite and > 0"));
    }
    let end = if letter == "D" {
        CURVE_D_END_IN
    } else {
        CURVES_END_IN
    };
    if t > end {
        return Err(format!(
            "Fig. UCS-66 curve {letter} is shipped to {end} in ({:.1} mm); tg = {t:.4} in",
            end * 25.4
        ));
    }
    let flat = t <= CHARPY_THICKNESS_IN;
    Ok(match letter {
        "A" if flat => 18.0,
        "A" => (-76.911 + 284.85 * t - 27.560 * t * t) / (1.0 + 1.7971 * t - 0.17887 * t * t),
        "B" if flat => -20.0,
        "B" => {
            let r = t.sqrt();
            -135.79 + 171.56 * r + 103.63 * t - 172.0 * t * r + 73.737 * t * t - 10.535 * t * t * r
        }
        "C" if flat => -55.0,
        "C" => {
            let u = 1.0 / t;
            101.29 + u * (-255.5 + u * (287.86 + u * (-196.42 + u * (69.457 - 9.8082 * u))))
        }
        "D" if t <= 0.5 => -55.0,
        "D" => {
            let x = (t - 0.5) * 16.0;
            let i = (x.floor() as usize).min(CURVE_D.len() - 2);
            let f = x - i as f64;
            CURVE_D[i] + f * (CURVE_D[i + 1] - CURVE_D[i])
        }
        _ => {
            return Err(format!(
                "curve \"{letter}\" is not one of Fig. UCS-66's A, B, C, D"
            ));
        }
    })
}

/// The Fig. UCS-66.1 temperature reduction at coincident ratio `rts`, °F (a
/// difference): 0 at 1 and above; `None` at 0.35 and below, where UCS-66(b)(3)
/// replaces the reduction by the −155 °F limit, and for a ratio that is not a
/// finite number.
pub fn reduction_f(rts: f64) -> Option<f64> {
    if !rts.is_finite() || rts <= 0.35 {
        None
    } else if rts >= 1.0 {
        Some(0.0)
    } else if rts > 0.6 {
        Some(100.0 * (1.0 - rts))
    } else {
        Some(
            -9979.57 - 14125.0 * rts.powf(1.5) + 9088.11 * rts.exp()
                - 17.3893 * rts.ln() / (rts * rts),
        )
    }
}

/// °F to °C.
pub fn celsius(f: f64) -> f64 {
    (f - 32.0) / 1.8
}
