//! Surface areas and enclosed volumes integrated from the exact NURBS patches match
//! closed forms derived independently here for every kind of head (with and without
//! straight flange), the shell course and the concentric reducer.

mod common;

use common::heads::head_kinds;
use std::f64::consts::{FRAC_PI_2, PI};

use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Reducer, ReducerAlignment, Shell, enclosed_volume, surface_area};

const OD: f64 = 2400.0;
const R: f64 = OD / 2.0;
const FLANGE: f64 = 50.0;
const RELATIVE: f64 = 1e-9;

/// Volume and area of a solid of revolution, as a pair that adds up piecewise.
#[derive(Clone, Copy, Debug)]
struct Measures {
    volume: f64,
    area: f64,
}

impl std::ops::Add for Measures {
    type Output = Measures;
    fn add(self, o: Measures) -> Measures {
        Measures {
            volume: self.volume + o.volume,
            area: self.area + o.area,
        }
    }
}

/// The knuckle band: the arc of radius `r` about (ρ = `a`, z = 0) from angle 0 to `phi`
/// (from +ρ towards +z) revolved; volume of the solid under it down to z = 0.
/// V = π∫₀ʰ (a + √(r² − t²))² dt with h = r sin φ; area by Pappus (arc length r φ,
/// centroid at radius a + r sin φ / φ).
fn knuckle_band(a: f64, r: f64, phi: f64) -> Measures {
    let h = r * phi.sin();
    let root_integral = 0.5 * (h * (r * r - h * h).sqrt() + r * r * (h / r).asin());
    Measures {
        volume: PI * (a * a * h + 2.0 * a * root_integral + r * r * h - h.powi(3) / 3.0),
        area: 2.0 * PI * (a * r * phi + r * r * phi.sin()),
    }
}

/// The spherical cap of height `h` on a sphere of radius `l` (zone area 2π l h).
fn spherical_cap(l: f64, h: f64) -> Measures {
    Measures {
        volume: PI * h * h * (3.0 * l - h) / 3.0,
        area: 2.0 * PI * l * h,
    }
}

/// The cone over a circle of radius `rho` closing to its apex at half-angle `alpha`.
fn cone(rho: f64, alpha: f64) -> Measures {
    Measures {
        volume: PI * rho * rho * (rho / alpha.tan()) / 3.0,
        area: PI * rho * rho / alpha.sin(),
    }
}

/// The straight flange or any cylinder of radius `r`, length `l` (lateral area).
fn cylinder(r: f64, l: f64) -> Measures {
    Measures {
        volume: PI * r * r * l,
        area: 2.0 * PI * r * l,
    }
}

/// The closed forms of a head without straight flange.
fn closed_form(kind: HeadKind) -> Measures {
    match kind {
        HeadKind::Hemispherical => Measures {
            volume: 2.0 / 3.0 * PI * R.powi(3),
            area: 2.0 * PI * R * R,
        },
        HeadKind::Ellipsoidal { ratio } => {
            // Half an oblate spheroid, semi-axes a (equatorial) > c (polar).
            let (a, c) = (R, R / ratio);
            let e = (1.0 - (c / a).powi(2)).sqrt();
            Measures {
                volume: 2.0 / 3.0 * PI * a * a * c,
                area: PI * a * a * (1.0 + (1.0 - e * e) / e * e.atanh()),
            }
        }
        HeadKind::Torispherical {
            crown_radius: l,
            knuckle_radius: r,
        } => {
            let a = R - r;
            let beta = (a / (l - r)).asin();
            knuckle_band(a, r, FRAC_PI_2 - beta) + spherical_cap(l, l * (1.0 - beta.cos()))
        }
        HeadKind::Toriconical {
            half_angle,
            knuckle_radius: r,
        } => {
            let alpha = half_angle.to_radians();
            let a = R - r;
            knuckle_band(a, r, alpha) + cone(a + r * alpha.cos(), alpha)
        }
        HeadKind::Conical {
            half_angle,
            small_diameter,
        } => {
            let alpha = half_angle.to_radians();
            let rs = small_diameter / 2.0;
            let h = (R - rs) / alpha.tan();
            Measures {
                volume: PI * h / 3.0 * (R * R + R * rs + rs * rs),
                area: PI * (R + rs) * (R - rs) / alpha.sin() + PI * rs * rs,
            }
        }
        HeadKind::Flat { knuckle_radius: r } => {
            let a = R - r;
            let plate = Measures {
                volume: 0.0,
                area: PI * a * a,
            };
            if r > 0.0 {
                knuckle_band(a, r, FRAC_PI_2) + plate
            } else {
                plate
            }
        }
    }
}

fn assert_close(what: &str, got: f64, expect: f64) {
    assert!(
        (got - expect).abs() <= RELATIVE * expect.abs(),
        "{what}: integrated {got}, closed form {expect}, relative error {:e}",
        (got - expect).abs() / expect.abs()
    );
}

fn kinds() -> Vec<HeadKind> {
    head_kinds(OD)
}

#[test]
fn textbook_values_of_the_common_heads() {
    // The closed forms above reduce to the textbook ones for these heads.
    let two_to_one = closed_form(HeadKind::TWO_TO_ONE);
    assert_close(
        "2:1 volume πD³/24",
        two_to_one.volume,
        PI * OD.powi(3) / 24.0,
    );
    let apex = closed_form(HeadKind::Conical {
        half_angle: 30.0,
        small_diameter: 0.0,
    });
    let h = R / 30f64.to_radians().tan();
    assert_close("cone volume πR²h/3", apex.volume, PI * R * R * h / 3.0);
    assert_close("cone area πR·slant", apex.area, PI * R * R.hypot(h));
    // A knuckle band of zero sweep is empty; a full quarter of a torus with a = 0 is a
    // hemisphere.
    let quarter = knuckle_band(0.0, R, FRAC_PI_2);
    assert_close(
        "hemisphere volume",
        quarter.volume,
        2.0 / 3.0 * PI * R.powi(3),
    );
    assert_close("hemisphere area", quarter.area, 2.0 * PI * R * R);
}

#[test]
fn head_volumes_and_areas_match_closed_forms() {
    for kind in kinds() {
        let expect = closed_form(kind);
        for flange in [0.0, FLANGE] {
            let head = Head::new(OD, kind).with_straight_flange(flange);
            let patches = head.patches().unwrap();
            let expect = expect + cylinder(R, flange);
            let what = format!("{} (flange {flange})", kind.name());
            // A plain flat head without flange encloses nothing: compare absolutely.
            if expect.volume == 0.0 {
                assert!(
                    enclosed_volume(&patches).abs() <= RELATIVE * R.powi(3),
                    "{what}"
                );
            } else {
                assert_close(
                    &format!("{what} volume"),
                    enclosed_volume(&patches),
                    expect.volume,
                );
            }
            assert_close(&format!("{what} area"), surface_area(&patches), expect.area);
        }
    }
}

#[test]
fn shell_area_and_flux() {
    let length = 6000.0;
    let patches = Shell {
        outside_diameter: OD,
        length,
    }
    .patches()
    .unwrap();
    assert_close("shell area πDL", surface_area(&patches), PI * OD * length);
    // Open at both ends: adding the flux through the far end disk, (L/3)·πR², gives
    // the enclosed volume πR²L.
    let closed = enclosed_volume(&patches) + length / 3.0 * PI * R * R;
    assert_close("shell volume", closed, PI * R * R * length);
}

#[test]
fn concentric_reducer_area_and_flux() {
    let (small, length) = (1500.0, 900.0);
    let patches = Reducer {
        large_diameter: OD,
        small_diameter: small,
        length,
        alignment: ReducerAlignment::Concentric,
    }
    .patches()
    .unwrap();
    let rs = small / 2.0;
    let slant = (R - rs).hypot(length);
    assert_close(
        "frustum area",
        surface_area(&patches),
        PI * (R + rs) * slant,
    );
    let frustum = PI * length / 3.0 * (R * R + R * rs + rs * rs);
    let closed = enclosed_volume(&patches) + length / 3.0 * PI * rs * rs;
    assert_close("frustum volume", closed, frustum);
}
