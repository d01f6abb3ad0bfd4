//! External pressure by ASME VIII-1 UG-28 (cylinders) and UG-33 (ellipsoidal,
//! torispherical and hemispherical heads), in the elastic range only.
//!
//! Factor A comes from the geometry formulas behind Section II-D Fig. G
//! (Windenburg–Trilling with ν = 0.3): a long cylinder buckles at
//! A = 1.1·(t/Do)², a short one at A = 1.30·(t/Do)^1.5 / (L/Do − 0.45·(t/Do)^0.5),
//! the smaller governing. Factor B is read off the material chart's elastic line
//! B = A·E/2 (the charts' left, straight part), because the charts themselves
//! are licensed. **Limit:** the elastic line is used only while the stress A·E is
//! at most half the specified minimum yield, [`ELASTIC_LIMIT`] · Sy; beyond it
//! the chart bends below the line and the result would be unconservative, so the
//! figure is refused with the reason. Then UG-28(c)(1): Pa = 4B / (3·Do/t) for
//! Do/t ≥ 10; a thicker cylinder (Do/t < 10, UG-28(c)(2)) is refused. UG-33:
//! A = 0.125 / (Ro/t), Pa = B / (Ro/t), with Ro the outside crown radius of a
//! torispherical head, the outside radius of a hemisphere, and K1·Do with
//! K1 = 0.9 for a 2:1 ellipsoidal head (Table UG-33.1; other ratios refused).

use serde::Serialize;

/// The fraction of Sy up to which the elastic line B = A·E/2 is taken.
pub const ELASTIC_LIMIT: f64 = 0.5;

/// One external-pressure result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct External {
    /// Paragraph, e.g. `UG-28(c)(1)`.
    pub paragraph: &'static str,
    /// Factor A (strain).
    pub a: f64,
    /// Factor B = A·E/2, MPa.
    pub b: f64,
    /// Allowable external pressure Pa, MPa.
    pub allowable: f64,
}

/// Factor A of a cylinder of outside diameter `do_`, wall `t` and unsupported
/// length `l` (mm): the smaller of the long- and short-cylinder formulas.
pub fn cylinder_factor_a(do_: f64, t: f64, l: f64) -> f64 {
    let r = t / do_;
    let long = 1.1 * r * r;
    let denom = l / do_ - 0.45 * r.sqrt();
    if denom <= 0.0 {
        // Shorter than the formula's reach: no elastic buckling, refused by the limit.
        return f64::INFINITY;
    }
    let short = 1.30 * r.powf(1.5) / denom;
    short.max(long)
}

fn elastic_b(a: f64, e: f64, sy: f64) -> Result<f64, String> {
    if a * e > ELASTIC_LIMIT * sy {
        return Err(format!(
            "A·E = {:.1} MPa exceeds {ELASTIC_LIMIT}·Sy = {:.1} MPa: beyond the elastic line \
             B = A·E/2; the material's external-pressure chart (Section II-D, licensed) is needed",
            a * e,
            ELASTIC_LIMIT * sy
        ));
    }
    Ok(a * e / 2.0)
}

/// UG-28(c)(1): the allowable external pressure of a cylinder, MPa, from outside
/// diameter `do_`, corroded wall `t`, unsupported length `l` (mm), modulus `e`
/// and yield `sy` (MPa).
pub fn cylinder(do_: f64, t: f64, l: f64, e: f64, sy: f64) -> Result<External, String> {
    if !(do_ > 0.0 && t > 0.0 && l > 0.0) {
        return Err(format!(
            "UG-28: Do = {do_}, t = {t}, L = {l} mm must be > 0"
        ));
    }
    let ratio = do_ / t;
    if ratio < 10.0 {
        return Err(format!(
            "UG-28(c)(2): Do/t = {ratio:.2} < 10 is not computed"
        ));
    }
    let a = cylinder_factor_a(do_, t, l);
    let b = elastic_b(a, e, sy)?;
    Ok(External {
        paragraph: "UG-28(c)(1)",
        a,
        b,
        allowable: 4.0 * b / (3.0 * ratio),
    })
}

/// UG-33: the allowable external pressure of a head of outside crown radius
/// `ro` and corroded wall `t` (mm), MPa (Pa = B/(Ro/t), A = 0.125/(Ro/t)).
pub fn head(ro: f64, t: f64, e: f64, sy: f64) -> Result<External, String> {
    if !(ro > 0.0 && t > 0.0) {
        return Err(format!("UG-33: Ro = {ro}, t = {t} mm must be > 0"));
    }
    let ratio = ro / t;
    let a = 0.125 / ratio;
    let b = elastic_b(a, e, sy)?;
    Ok(External {
        paragraph: "UG-33(d)/(e)",
        a,
        b,
        allowable: b / ratio,
    })
}

/// Ro of a 2:1 ellipsoidal head of outside diameter `do_`: K1·Do with K1 = 0.9
/// (Table UG-33.1 at D/2h = 2); other ratios are refused.
pub fn ellipsoidal_ro(do_: f64, ratio: f64) -> Result<f64, String> {
    if (ratio - 2.0).abs() > 1e-9 {
        return Err(format!(
            "UG-33(d): only the 2:1 ellipsoidal head's K1 = 0.9 is shipped (D/2h = {ratio})"
        ));
    }
    Ok(0.9 * do_)
}

/// The elastic-line check at the thickness a `required_*` function found.
fn check_elastic(a: f64, e: f64, sy: f64, what: &str) -> Result<(), String> {
    elastic_b(a, e, sy)
        .map(|_| ())
        .map_err(|why| format!("{what}: the required thickness is outside the elastic line: {why}"))
}

/// UG-28(c)(1) inverted: the corroded wall a cylinder of outside diameter `do_`
/// and unsupported length `l` (mm) needs to carry external pressure `p` MPa,
/// mm, found by bisection on the (increasing) allowable pressure to 1e-9 of
/// `do_`; an error when it is thicker than Do/10 or outside the elastic line.
pub fn required_cylinder(do_: f64, l: f64, e: f64, sy: f64, p: f64) -> Result<f64, String> {
    if !(do_ > 0.0 && l > 0.0 && p > 0.0 && e > 0.0) {
        return Err(format!(
            "UG-28: Do = {do_}, L = {l} mm, P = {p} MPa, E = {e} MPa must be > 0"
        ));
    }
    let allowable = |t: f64| 4.0 * cylinder_factor_a(do_, t, l) * e / 2.0 / (3.0 * do_ / t);
    let (mut lo, mut hi) = (0.0, do_ / 10.0);
    if allowable(hi) < p {
        return Err(format!(
            "UG-28(c)(2): {p} MPa would need a wall thicker than Do/10 = {hi:.2} mm"
        ));
    }
    while hi - lo > 1e-9 * do_ {
        let mid = 0.5 * (lo + hi);
        if allowable(mid) < p {
            lo = mid
        } else {
            hi = mid
        }
    }
    check_elastic(cylinder_factor_a(do_, hi, l), e, sy, "UG-28")?;
    Ok(hi)
}

/// UG-28(c)(1) for a cylinder of any length, the long-cylinder branch
/// A = 1.1·(t/Do)² (the least A, so the thickest wall, of every length):
/// Pa = (2.2/3)·E·(t/Do)³ gives t = Do·(3·P/(2.2·E))^(1/3), mm.
pub fn required_long_cylinder(do_: f64, e: f64, sy: f64, p: f64) -> Result<f64, String> {
    if !(do_ > 0.0 && p > 0.0 && e > 0.0) {
        return Err(format!(
            "UG-28: Do = {do_} mm, P = {p} MPa, E = {e} MPa must be > 0"
        ));
    }
    let t = do_ * (3.0 * p / (2.2 * e)).cbrt();
    check_elastic(1.1 * (t / do_).powi(2), e, sy, "UG-28")?;
    Ok(t)
}

/// UG-33 inverted for a head of outside crown radius `ro` mm: in the elastic
/// range Pa = B/(Ro/t) = 0.0625·E·(t/Ro)², so t = 4·Ro·(P/E)^0.5, mm.
pub fn required_head(ro: f64, e: f64, sy: f64, p: f64) -> Result<f64, String> {
    if !(ro > 0.0 && p > 0.0 && e > 0.0) {
        return Err(format!(
            "UG-33: Ro = {ro} mm, P = {p} MPa, E = {e} MPa must be > 0"
        ));
    }
    let t = 4.0 * ro * (p / e).sqrt();
    check_elastic(0.125 * t / ro, e, sy, "UG-33")?;
    Ok(t)
}
