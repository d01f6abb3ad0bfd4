//! The lateral loads on a vertical vessel's supports: its outline for the wind
//! ([`super::wind`]), its operating mass along its height for the earthquake
//! ([`super::seismic`]), and the allowable-stress load combinations of ASCE 7-16
//! §2.4.1 at a horizontal plane (a skirt's base, the legs' floor, the lugs'
//! bearing plane).
//!
//! Mass distribution (a choice: the weight model gives totals and centres): the
//! pressure envelope's walls spread uniformly over the stack's height, the
//! liquid uniformly from the stack's bottom up to its level, every other metal
//! item (skirt, legs, lugs, nozzles, pads) at its centre.
//!
//! Combinations (ρ = 1, Ev = 0.2·SDS·D of §12.4.2.2): D alone (operating and
//! hydrotest), D + 0.6W (operating), 0.6D + 0.6W (empty: uplift),
//! (1 + 0.14·SDS)D + 0.7E and (0.6 − 0.14·SDS)D + 0.7E (operating). The hydrotest
//! is not combined with wind.

use serde::Serialize;

use super::GRAVITY;
use super::seismic::{self, Coefficient, Mass};
use super::wind::{self, Band, WindFactors};
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{SeismicDesign, VesselDesign};
use crate::weights::Weights;

/// A vessel's lateral-load model.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Lateral {
    /// Elevation above grade of the vessel frame's z = 0 (the datum), mm: the
    /// wind's `base_elevation` (default 0) above the vessel's lowest point.
    pub datum: f64,
    /// The lowest point of the vessel and its supports, vessel frame, mm: the
    /// base the seismic heights are measured from.
    pub base: f64,
    /// The outline, heights above grade.
    pub bands: Vec<Band>,
    /// The operating mass along the height, heights above [`Lateral::base`].
    pub masses: Vec<Mass>,
    /// Weights, N: empty, operating, hydrotest.
    pub empty: f64,
    /// Operating weight, N.
    pub operating: f64,
    /// Hydrotest weight, N.
    pub test: f64,
    /// The wind's factors, when the design gives wind.
    pub wind: Option<WindFactors>,
    /// The earthquake's inputs and coefficient, when the design gives one.
    pub seismic: Option<(SeismicDesign, Coefficient)>,
}

/// One load combination at a plane.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LoadCase {
    /// The combination, e.g. `D + 0.6W (operating)`.
    pub name: &'static str,
    /// Factored weight above the plane, N (downward positive).
    pub weight: f64,
    /// Factored overturning moment at the plane, N·mm.
    pub moment: f64,
    /// Factored shear at the plane, N.
    pub shear: f64,
    /// Whether the case includes wind or earthquake (UG-23(d)'s 1.2 applies).
    pub lateral: bool,
}

impl Lateral {
    /// The model of vertical vessel `design` resolved as `resolved`, weighed as `w`.
    pub fn of(design: &VesselDesign, resolved: &ResolvedVessel, w: &Weights) -> Lateral {
        let base = resolved.extent.0;
        let elevation = design
            .design
            .wind
            .as_ref()
            .and_then(|w| w.base_elevation)
            .unwrap_or(0.0);
        let datum = elevation - base;
        let mut bands = Vec::new();
        let (mut stack_lo, mut stack_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &resolved.parts {
            let (z0, z1) = (p.span.0.min(p.span.1), p.span.0.max(p.span.1));
            let width = match &p.geometry {
                PartGeometry::Shell(s) => s.outside_diameter,
                PartGeometry::Head(h) => h.outside_diameter,
                PartGeometry::Reducer(r) => r.large_diameter,
                PartGeometry::Skirt(s) => {
                    s.top_diameter + 2.0 * s.height * s.flare_angle.to_radians().tan()
                }
                PartGeometry::Legs(l) => f64::from(l.count) * l.pipe_diameter,
                _ => continue,
            };
            if matches!(
                p.geometry,
                PartGeometry::Shell(_) | PartGeometry::Head(_) | PartGeometry::Reducer(_)
            ) {
                stack_lo = stack_lo.min(z0);
                stack_hi = stack_hi.max(z1);
            }
            bands.push(Band {
                id: "",
                bottom: datum + z0,
                top: datum + z1,
                width,
            });
        }
        let mut masses: Vec<Mass> = w
            .items
            .iter()
            .map(|i| Mass::Point {
                h: i.centre.z - base,
                mass: i.mass,
            })
            .collect();
        if stack_hi > stack_lo {
            masses.push(Mass::Uniform {
                h0: stack_lo - base,
                h1: stack_hi - base,
                mass: w.walls,
            });
        }
        // The liquid from the stack's bottom up to its level.
        let level = design.operating.map_or(0.0, |o| o.liquid_level);
        if w.liquid > 0.0 && stack_hi > stack_lo {
            let (h0, h1) = (stack_lo - base, stack_lo + level - base);
            if h1 > h0 {
                masses.push(Mass::Uniform {
                    h0,
                    h1,
                    mass: w.liquid,
                });
            } else {
                masses.push(Mass::Point {
                    h: h0,
                    mass: w.liquid,
                });
            }
        }
        let c = &design.design;
        Lateral {
            datum,
            base,
            bands,
            masses,
            empty: w.empty * GRAVITY,
            operating: w.operating * GRAVITY,
            test: w.test * GRAVITY,
            wind: c.wind.as_deref().map(WindFactors::of),
            seismic: c.seismic.as_deref().map(|s| (*s, seismic::coefficient(s))),
        }
    }

    /// The wind's shear (N) and moment (N·mm) at vessel-frame height `z`.
    pub fn wind_at(&self, z: f64) -> Option<(f64, f64)> {
        let f = self.wind.as_ref()?;
        Some(wind::shear_and_moment(f, &self.bands, self.datum + z))
    }

    /// The earthquake's base shear (N), and its shear and moment at vessel-frame
    /// height `z`.
    pub fn seismic_at(&self, z: f64) -> Option<(f64, f64, f64)> {
        let (_, c) = self.seismic.as_ref()?;
        let v = c.cs * self.operating;
        let (s, m) = seismic::shear_and_moment(v, c.k, &self.masses, z - self.base);
        Some((v, s, m))
    }

    /// The combinations at vessel-frame height `z`, with `below` N of the
    /// operating, empty and test weights lying below the plane (e.g. the skirt
    /// under its top) taken off each.
    pub fn cases(&self, z: f64, below: f64) -> Vec<LoadCase> {
        let (op, empty, test) = (
            self.operating - below,
            self.empty - below,
            self.test - below,
        );
        let mut out = vec![
            LoadCase {
                name: "D (operating)",
                weight: op,
                moment: 0.0,
                shear: 0.0,
                lateral: false,
            },
            LoadCase {
                name: "D (hydrotest)",
                weight: test,
                moment: 0.0,
                shear: 0.0,
                lateral: false,
            },
        ];
        if let Some((v, m)) = self.wind_at(z) {
            out.push(LoadCase {
                name: "D + 0.6W (operating)",
                weight: op,
                moment: 0.6 * m.abs(),
                shear: 0.6 * v,
                lateral: true,
            });
            out.push(LoadCase {
                name: "0.6D + 0.6W (empty)",
                weight: 0.6 * empty,
                moment: 0.6 * m.abs(),
                shear: 0.6 * v,
                lateral: true,
            });
        }
        if let (Some((_, v, m)), Some((s, _))) = (self.seismic_at(z), &self.seismic) {
            let ev = 0.14 * s.sds;
            out.push(LoadCase {
                name: "(1 + 0.14·SDS)D + 0.7E (operating)",
                weight: (1.0 + ev) * op,
                moment: 0.7 * m.abs(),
                shear: 0.7 * v,
                lateral: true,
            });
            out.push(LoadCase {
                name: "(0.6 − 0.14·SDS)D + 0.7E (operating)",
                weight: (0.6 - ev) * op,
                moment: 0.7 * m.abs(),
                shear: 0.7 * v,
                lateral: true,
            });
        }
        out
    }
}
