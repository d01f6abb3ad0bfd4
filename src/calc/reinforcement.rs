//! UG-37 reinforcement of an opening by area replacement, internal pressure,
//! for a radial nozzle set through the wall (Fig. UG-37.1, no inward projection),
//! with or without a reinforcing pad: the area the opening removes, A = d·tr·F,
//! against what the corroded wall (A1), the neck (A2), the fillet welds (A41 at
//! the neck, A42 at the pad's rim) and the pad (A5) give within the limits of
//! reinforcement — parallel to the wall, max(d, Rn + tn + t) each side of the
//! axis; normal to it, min(2.5·t, 2.5·tn + te).
//!
//! Choices where the code leaves them to the designer: neck, wall and pad are of
//! one material, so every strength reduction factor fr = 1; F = 1 (a radial
//! nozzle; E1 = 1, the opening clear of welded seams); welds are the smallest
//! UW-16(d) allows — the neck's throat min(6 mm, 0.7·t_min) with t_min the lesser
//! of 19 mm, tn and the wall (or pad), the pad rim's throat 0.5·min(19 mm, te, t)
//! — counted as legs² (leg = throat / 0.7071). UG-36(c)(3) exempts small
//! openings; UG-36(b)(1)'s size limit is reported, not enforced (Appendix 1-7
//! would then also apply).
//!
//! Under external pressure, UG-37(d)(1): the same areas with half the required
//! area, A = 0.5·d·tr, where tr is the host's and trn the neck's wall required
//! by the external-pressure rules ([`reinforcement_external`]); a vessel under
//! both is checked for each.

use serde::Serialize;

use super::CalcError;
use super::error::{non_negative, positive};

/// What UG-37 needs of one opening, mm and MPa.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opening {
    /// Pressure on the host at the opening, MPa.
    pub pressure: f64,
    /// Allowable stress of neck, wall and pad at the design temperature, MPa.
    pub stress: f64,
    /// Corrosion allowance (inside), mm.
    pub corrosion_allowance: f64,
    /// Neck outside diameter, mm.
    pub neck_od: f64,
    /// Neck nominal wall, mm.
    pub neck_wall: f64,
    /// Host nominal wall, mm.
    pub wall: f64,
    /// tr: the host's required thickness at E = 1, corroded, without corrosion
    /// allowance, mm.
    pub wall_required: f64,
    /// Inside diameter of the host (for UG-36(b)(1)), mm.
    pub host_diameter: f64,
    /// Reinforcing pad `(outside diameter, thickness)`, mm.
    pub pad: Option<(f64, f64)>,
}

/// The UG-37 figures of one opening, mm and mm².
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Reinforcement {
    /// The paragraph: `UG-37(c)` (internal) or `UG-37(d)(1)` (external).
    pub paragraph: &'static str,
    /// d: finished opening diameter, corroded, mm.
    pub d: f64,
    /// t: host wall, corroded, mm.
    pub t: f64,
    /// tr: host required thickness (E = 1), mm.
    pub tr: f64,
    /// tn: neck wall, corroded, mm.
    pub tn: f64,
    /// trn: neck required thickness, UG-27(c)(1) at E = 1, mm.
    pub trn: f64,
    /// te: pad thickness (0 without a pad), mm.
    pub te: f64,
    /// Limit parallel to the wall, each side of the axis, mm.
    pub limit_parallel: f64,
    /// Limit normal to the wall, outside, mm.
    pub limit_normal: f64,
    /// A: area required, mm².
    pub a_required: f64,
    /// A1: excess in the host wall, mm².
    pub a1: f64,
    /// A2: excess in the neck outside the wall, mm².
    pub a2: f64,
    /// A3: inward projection (none in the model), mm².
    pub a3: f64,
    /// A41: neck-to-wall (or neck-to-pad) fillet weld, mm².
    pub a41: f64,
    /// A42: pad rim fillet weld, mm².
    pub a42: f64,
    /// A5: pad within the parallel limit, mm².
    pub a5: f64,
    /// A1 + A2 + A3 + A41 + A42 + A5, mm².
    pub a_available: f64,
    /// A_available − A_required, mm² (negative: deficient).
    pub margin: f64,
    /// The UG-36(c)(3) clause that exempts the opening from the calculation.
    pub exempt: Option<&'static str>,
    /// A note on the opening's size (UG-36(b)(1)), when it exceeds the limit.
    pub note: Option<String>,
}

impl Reinforcement {
    /// Whether the opening lacks reinforcement (and is not exempt).
    pub fn deficient(&self) -> bool {
        self.exempt.is_none() && self.margin < 0.0
    }
}

/// UW-16(d) minimum fillet leg for a throat of `throat` mm.
fn leg(throat: f64) -> f64 {
    throat / std::f64::consts::FRAC_1_SQRT_2
}

/// The UG-37(c) area replacement of `o` under internal pressure.
pub fn reinforcement(o: &Opening) -> Result<Reinforcement, CalcError> {
    area_replacement(o, 1.0, None, "UG-37(c)")
}

/// UG-37(d)(1): the area replacement of `o` under external pressure
/// `o.pressure`, with `o.wall_required` the host's and `neck_required` the
/// neck's corroded wall required by UG-28 / UG-33 (mm): A = 0.5·d·tr.
pub fn reinforcement_external(o: &Opening, neck_required: f64) -> Result<Reinforcement, CalcError> {
    non_negative("opening", "neck_required", neck_required)?;
    area_replacement(o, 0.5, Some(neck_required), "UG-37(d)(1)")
}

/// The area replacement of `o` with required area `factor`·d·tr and the neck's
/// required wall `neck_required` (UG-27(c)(1) at E = 1 when `None`).
fn area_replacement(
    o: &Opening,
    factor: f64,
    neck_required: Option<f64>,
    paragraph: &'static str,
) -> Result<Reinforcement, CalcError> {
    const E: &str = "opening";
    positive(E, "pressure", o.pressure)?;
    positive(E, "stress", o.stress)?;
    non_negative(E, "corrosion_allowance", o.corrosion_allowance)?;
    positive(E, "neck_od", o.neck_od)?;
    positive(E, "wall", o.wall)?;
    non_negative(E, "wall_required", o.wall_required)?;
    positive(E, "host_diameter", o.host_diameter)?;
    let ca = o.corrosion_allowance;
    let tn = o.neck_wall - ca;
    positive(E, "neck_wall less corrosion", tn)?;
    let t = o.wall - ca;
    positive(E, "wall less corrosion", t)?;
    let (dp, te) = match o.pad {
        Some((dp, te)) => (
            positive(E, "pad_od", dp)?,
            positive(E, "pad_thickness", te)?,
        ),
        None => (0.0, 0.0),
    };
    let d = o.neck_od - 2.0 * tn;
    positive(E, "d", d)?;
    let rn = d / 2.0;
    let p = o.pressure;
    let trn = neck_required.unwrap_or(p * rn / (o.stress - 0.6 * p));
    let tr = o.wall_required;
    let limit_parallel = d.max(rn + tn + t);
    let limit_normal = (2.5 * t).min(2.5 * tn + te);
    let a_required = factor * d * tr;
    let a1 = (d.max(2.0 * (t + tn)) * (t - tr)).max(0.0);
    let excess_neck = (tn - trn).max(0.0);
    let a2 = if te > 0.0 {
        (5.0 * excess_neck * t).min(2.0 * excess_neck * (2.5 * tn + te))
    } else {
        (5.0 * excess_neck * t).min(5.0 * excess_neck * tn)
    };
    let neck_joined = if te > 0.0 { te } else { t };
    let a41 = leg(6.0_f64.min(0.7 * 19.0_f64.min(tn).min(neck_joined))).powi(2);
    let (a42, a5) = if te > 0.0 {
        let width = dp.min(2.0 * limit_parallel) - d - 2.0 * tn;
        (
            leg(0.5 * 19.0_f64.min(te).min(t)).powi(2),
            width.max(0.0) * te,
        )
    } else {
        (0.0, 0.0)
    };
    let a_available = a1 + a2 + a41 + a42 + a5;
    // UG-36(c)(3): openings needing no calculation (finished opening, new).
    let finished = o.neck_od - 2.0 * o.neck_wall;
    let exempt = if finished <= 60.0 {
        Some("UG-36(c)(3)(a): finished opening ≤ 60 mm (2 3/8 in)")
    } else if finished <= 89.0 && o.wall <= 10.0 {
        Some("UG-36(c)(3)(a): finished opening ≤ 89 mm (3 1/2 in) in a wall ≤ 10 mm (3/8 in)")
    } else {
        None
    };
    let limit = if o.host_diameter <= 1524.0 {
        (o.host_diameter / 2.0).min(508.0)
    } else {
        (o.host_diameter / 3.0).min(1016.0)
    };
    let note = (d > limit).then(|| {
        format!(
            "UG-36(b)(1): opening d = {d:.1} mm exceeds {limit:.1} mm; Appendix 1-7 also \
             applies and is not calculated"
        )
    });
    Ok(Reinforcement {
        paragraph,
        d,
        t,
        tr,
        tn,
        trn,
        te,
        limit_parallel,
        limit_normal,
        a_required,
        a1,
        a2,
        a3: 0.0,
        a41,
        a42,
        a5,
        a_available,
        margin: a_available - a_required,
        exempt,
        note,
    })
}
