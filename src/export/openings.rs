//! A vessel's openings and their cuts, one routine for the direct scene build
//! ([`build_scene`](super::build_scene), the GLB) and the exchange writers
//! (`exchange::source`, STEP and IGES), so that the two cannot drift apart:
//! [`openings`] lists what is cut into what (every boot's shell, then every
//! nozzle's neck, in design order, each with its pad) and [`cut_opening`]
//! cuts one with `mesh`'s [`OpeningPlan`]. The callers differ only in the
//! frames and tolerance they pass: the scene turns each head so that its seam
//! lies away from its openings, the exchange keeps the seam where the design
//! puts it (it cuts across seams itself), and the two loops are one curve in
//! the vessel frame. Openings whose canonical march is the same (in a plant,
//! every nozzle of one size and pad on courses of one diameter;
//! [`OpeningPlan::shared_key`]) are placed from one march kept in
//! [`SharedMarches`], which changes no bit of any cut.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

use glam::DAffine3;

use crate::constraints::ResolvedVessel;
use crate::mesh::{AxialCut, OpeningPlan, ReusableCut};
use crate::parts::Patch;

/// One opening of a vessel: a node cut into another. Nodes are numbered as
/// the scene and the exchange number them: the vessel's parts in design
/// order, then its nozzles in design order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opening {
    /// The boot's or nozzle's node, whose first patch is cut into the host.
    pub neck: usize,
    /// The host part's node.
    pub host: usize,
    /// The reinforcing pad's outside diameter, mm.
    pub pad_od: Option<f64>,
}

/// The openings of `vessel`: every boot (a part with a host) in design order,
/// then every nozzle in design order.
pub fn openings(vessel: &ResolvedVessel) -> Vec<Opening> {
    let parts = vessel.parts.len();
    let boots = vessel.parts.iter().enumerate().filter_map(|(i, part)| {
        part.host.map(|host| Opening {
            neck: i,
            host,
            pad_od: None,
        })
    });
    let necks = vessel
        .nozzles
        .iter()
        .enumerate()
        .map(|(i, nozzle)| Opening {
            neck: parts + i,
            host: nozzle.host,
            pad_od: nozzle.pad.map(|p| p.0),
        });
    boots.chain(necks).collect()
}

/// Canonical marches by their [`OpeningPlan::shared_key`], kept for the
/// length of one export (across its vessels and threads).
#[derive(Debug, Default)]
pub struct SharedMarches {
    cuts: Mutex<HashMap<u128, Arc<AxialCut>>>,
    /// Whether to share at all (off only to check that sharing changes
    /// nothing).
    off: bool,
}

impl SharedMarches {
    /// A table that never shares: every opening is marched.
    pub fn unshared() -> Self {
        Self {
            cuts: Mutex::default(),
            off: true,
        }
    }

    fn get(&self, key: u128) -> Option<Arc<AxialCut>> {
        let cuts = self.cuts.lock().unwrap_or_else(PoisonError::into_inner);
        cuts.get(&key).cloned()
    }

    fn keep(&self, key: u128, cut: &Arc<AxialCut>) {
        let mut cuts = self.cuts.lock().unwrap_or_else(PoisonError::into_inner);
        cuts.entry(key).or_insert_with(|| cut.clone());
    }
}

/// Cuts `opening`: `neck`'s patch (the node's first) placed by `nozzle_frame`
/// into the host's patches `hosts` placed by `host_frame`, to `tolerance` mm,
/// from a march in `shared` when one fits.
///
/// # Errors
///
/// The message of the cut's error, or that the neck's node has no patch.
pub fn cut_opening(
    neck: Option<&Patch>,
    pad_od: Option<f64>,
    (nozzle_frame, host_frame): (&DAffine3, &DAffine3),
    hosts: &[Patch],
    tolerance: f64,
    shared: &SharedMarches,
) -> Result<ReusableCut, String> {
    let Some(neck) = neck else {
        return Err("the part has no patch to cut into its host".to_string());
    };
    let plan = OpeningPlan::new(
        neck,
        pad_od,
        nozzle_frame,
        host_frame,
        hosts.iter().collect(),
        tolerance,
    );
    let key = if shared.off { None } else { plan.shared_key() };
    let kept = key.and_then(|k| shared.get(k));
    let cut = plan.cut(kept.as_ref()).map_err(|e| e.to_string())?;
    if let (Some(key), Some(axial)) = (key, &cut.axial) {
        shared.keep(key, axial);
    }
    Ok(cut)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::resolve;
    use crate::plant::generate_plant;

    /// Every opening of a generated plant, cut with one table and with none:
    /// the same cuts bit for bit, and some placed from another's march.
    #[test]
    fn shared_marches_change_no_cut() {
        let design = generate_plant(6, 1).expect("plant");
        let resolved = resolve(&design).expect("resolves");
        let (shared, unshared) = (SharedMarches::default(), SharedMarches::unshared());
        let (mut placed, mut total) = (0, 0);
        for vessel in &resolved {
            let mut nodes: Vec<(Vec<Patch>, DAffine3)> = Vec::new();
            for part in &vessel.parts {
                nodes.push((part.geometry.patches().expect("patches"), part.frame));
            }
            for nozzle in &vessel.nozzles {
                nodes.push((nozzle.geometry.patches().expect("patches"), nozzle.frame));
            }
            for opening in openings(vessel) {
                let (neck, host) = (&nodes[opening.neck], &nodes[opening.host]);
                let cut = |table| {
                    cut_opening(
                        neck.0.first(),
                        opening.pad_od,
                        (&neck.1, &host.1),
                        &host.0,
                        0.01,
                        table,
                    )
                    .expect("cuts")
                };
                let (a, b) = (cut(&shared), cut(&unshared));
                assert_eq!((&a.cut, &a.pad), (&b.cut, &b.pad), "{}", vessel.tag);
                placed += usize::from(a.reused);
                total += 1;
            }
        }
        assert!(placed > 0, "none of {total} openings placed from a march");
    }
}
