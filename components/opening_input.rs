//! What an opening was last cut from ([`OpeningInput`], a nozzle's component
//! beside its `Opening`): the Geometry stage's `systems::cut_openings` compares a dirty
//! opening's inputs with it to skip a cut that would come out the same, and takes
//! its kept canonical cut to place an opening that only moved along its course.

use std::sync::Arc;

use bevy_ecs::component::Component;
use glam::DAffine3;

use crate::mesh::AxialCut;
use crate::parts::Patch;

/// What an opening was last cut from: the neck and host patches (held, so the
/// pointers compared cannot be reused), the pad, the tolerance and the two
/// relative placements the cut and the pad patch are computed with. When all are
/// the same — bit for bit, as when a course below moves both the host and the
/// nozzle by a whole number of millimetres — cutting again would give the same
/// opening, so it is skipped. With the same neck (or, for a plain neck, the same
/// canonical neck: a projection edit), pad and tolerance, an opening in a
/// straight course that only moved along the course's axis is placed again from
/// the kept [`AxialCut`] without marching.
#[derive(Component, Clone, Debug)]
#[component(storage = "SparseSet")]
pub struct OpeningInput {
    neck: Arc<Patch>,
    hosts: Vec<Arc<Patch>>,
    pad_od: Option<f64>,
    tolerance: f64,
    /// `host_frame⁻¹ · nozzle_frame` (the cut's placement).
    nozzle_in_host: DAffine3,
    /// `nozzle_frame⁻¹ · host_frame` (the pad patch's placement).
    host_in_nozzle: DAffine3,
    /// The loops on the canonical host, when the opening lies in a straight course.
    pub(crate) axial: Option<Arc<AxialCut>>,
}

impl OpeningInput {
    /// The inputs of a cut of `neck` (placed by `frame`) into `hosts` (placed by
    /// `host_frame`), with its pad and tolerance, keeping `axial`.
    pub(crate) fn new(
        neck: Arc<Patch>,
        hosts: Vec<Arc<Patch>>,
        pad_od: Option<f64>,
        tolerance: f64,
        frame: DAffine3,
        host_frame: DAffine3,
        axial: Option<Arc<AxialCut>>,
    ) -> Self {
        Self {
            neck,
            hosts,
            pad_od,
            tolerance,
            nozzle_in_host: host_frame.inverse() * frame,
            host_in_nozzle: frame.inverse() * host_frame,
            axial,
        }
    }

    /// The kept canonical cut, if the opening is cut again with the same pad
    /// and tolerance, and the same neck or a kept cut marched on a canonical
    /// neck (which the cut compares with the new neck's: a projection edit keeps
    /// it). It then applies wherever the nozzle moved along the course's axis.
    pub(crate) fn kept_for(
        &self,
        neck: &Arc<Patch>,
        pad_od: Option<f64>,
        tolerance: f64,
    ) -> Option<Arc<AxialCut>> {
        let axial = self.axial.as_ref()?;
        let neck = Arc::ptr_eq(&self.neck, neck) || axial.reach().is_some();
        let same = neck
            && self.pad_od.map(f64::to_bits) == pad_od.map(f64::to_bits)
            && self.tolerance.to_bits() == tolerance.to_bits();
        same.then(|| axial.clone())
    }

    /// Heap bytes held besides the kept canonical cut (shared between openings;
    /// the patches are the model's).
    pub fn heap_bytes(&self) -> usize {
        self.hosts.capacity() * std::mem::size_of::<Arc<Patch>>()
    }

    /// The kept canonical cut, if any.
    pub fn axial(&self) -> Option<&AxialCut> {
        self.axial.as_deref()
    }

    /// Same inputs: same patches (by identity), equal numbers, equal bits.
    pub(crate) fn same(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.neck, &other.neck)
            && self.hosts.len() == other.hosts.len()
            && self
                .hosts
                .iter()
                .zip(&other.hosts)
                .all(|(a, b)| Arc::ptr_eq(a, b))
            && self.pad_od.map(f64::to_bits) == other.pad_od.map(f64::to_bits)
            && self.tolerance.to_bits() == other.tolerance.to_bits()
            && bits(&self.nozzle_in_host) == bits(&other.nozzle_in_host)
            && bits(&self.host_in_nozzle) == bits(&other.host_in_nozzle)
    }
}

/// The bit patterns of an affine map's twelve numbers.
fn bits(a: &DAffine3) -> [u64; 12] {
    let m = a.to_cols_array();
    std::array::from_fn(|k| m[k].to_bits())
}
