//! Canonical cuts shared between openings: every opening whose canonical march
//! (see `mesh::axial` and `mesh::turn`) would be the same is placed from one.
//!
//! Part of cutting openings (the Geometry stage's `cut_openings`). A canonical
//! march depends on the course's cross-section, the nozzle's canonical
//! placement (in a round course: whatever way it faces), its canonical neck
//! (for a plain neck: its radius and the host's reach, not its projection), its
//! pad and the tolerance. Openings that agree on all of these, bit for bit, get
//! the very same [`AxialCut`] — in a plant, every nozzle of one size, schedule and
//! pad on courses of one diameter. An opening's plan
//! ([`OpeningPlan::shared_key`](crate::mesh::OpeningPlan::shared_key)) names that
//! march before any marching; [`SharedCuts`] keeps the cuts in use by it, so a full build marches
//! each distinct one once, and a diameter edit finds the cuts of every nozzle
//! size some other course of the new diameter already has. Like the mesh
//! table (`mesh::instances`) it holds weak references: a cut lives as long as an
//! opening keeps it, and sharing never changes a bit of any opening (placing a
//! kept cut gives what a fresh march gives).

use crate::mesh::store::Key;

use super::AxialCut;
use crate::mesh::store::WeakTable;

/// A 128-bit key of the canonical march an opening in a one-patch straight
/// course is placed from: the course and canonical placement (`course`, by
/// `mesh::axial`'s key), the canonical neck's radius and height (`reach`), the
/// pad's OD and the tolerance, all by their exact bits (see
/// [`OpeningPlan::shared_key`](crate::mesh::OpeningPlan::shared_key)). Two
/// openings with one key are cut from the same march; the cut itself still
/// checks, when placed, that it fits the opening (`AxialCut::fits`).
pub(in crate::mesh) fn shared_key(
    course: u128,
    (radius, height): (u64, u64),
    pad_od: Option<f64>,
    tolerance: f64,
) -> u128 {
    let mut key = Key::with_capacity(6);
    key.write_u128(course);
    key.write(radius);
    key.write(height);
    key.write(pad_od.map_or(u64::MAX, f64::to_bits));
    key.write(tolerance.to_bits());
    key.finish()
}

/// The canonical cuts in use, by their `shared_key`: weak references, so an
/// entry dies with the last opening keeping its cut (dead entries are swept as
/// the table grows).
pub type SharedCuts = WeakTable<AxialCut>;

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DVec3};

    use super::*;
    use crate::mesh::test_parts::{course, frame, neck};
    use crate::mesh::{OpeningPlan, cut_opening_reusing};

    fn key(projection: f64, pad: Option<f64>, angle: f64, z: f64) -> Option<u128> {
        let (s, c) = angle.sin_cos();
        let at = frame(DVec3::new(0.0, 0.0, z), DVec3::new(c, s, 0.0));
        let (neck, course) = (neck(projection), course());
        OpeningPlan::new(&neck, pad, &at, &DAffine3::IDENTITY, vec![&course], 1.0).shared_key()
    }

    #[test]
    fn one_key_whatever_the_projection_orientation_and_elevation() {
        let k = key(1400.0, None, 0.3, 1500.0).expect("a plain neck in a course");
        assert_eq!(key(1600.0, None, 2.9, 900.0), Some(k));
        assert_eq!(key(1400.0, None, -1.2, 2100.0), Some(k));
        assert_ne!(key(1400.0, Some(450.0), 0.3, 1500.0), Some(k));
        assert_ne!(
            key(1400.0, Some(450.0), 0.3, 1500.0),
            key(1400.0, Some(460.0), 0.3, 1500.0)
        );
    }

    #[test]
    fn openings_with_one_key_are_placed_from_one_cut() {
        let course = course();
        let cut = |projection: f64, angle: f64, z: f64, kept| {
            let (s, c) = angle.sin_cos();
            let at = frame(DVec3::new(0.0, 0.0, z), DVec3::new(c, s, 0.0));
            cut_opening_reusing(
                &neck(projection),
                Some(450.0),
                &at,
                &DAffine3::IDENTITY,
                &[&course],
                1.0,
                kept,
            )
            .unwrap()
        };
        let first = cut(1400.0, 0.3, 1500.0, None);
        let shared = first.axial.clone().unwrap();
        let mut table = SharedCuts::default();
        table.insert(7, &shared);
        let kept = table.get(7).unwrap();
        for (projection, angle, z) in [(1600.0, 2.9, 900.0), (1400.0, -1.2, 2100.0)] {
            let placed = cut(projection, angle, z, Some(&kept));
            assert!(placed.reused);
            assert_eq!(placed.cut, cut(projection, angle, z, None).cut);
            // The pad's patch and its trims on it do not change (only the
            // neck (u, v) of its inner trim follow the neck's length).
            let (pad, first_pad) = (placed.pad.unwrap(), first.pad.as_ref().unwrap());
            assert_eq!(pad.patch, first_pad.patch);
            assert_eq!(pad.outer.host_uv, first_pad.outer.host_uv);
            assert_eq!(pad.inner.host_uv, first_pad.inner.host_uv);
        }
        drop((first, shared, kept));
        assert!(
            table.get(7).is_none(),
            "dies with the last opening keeping it"
        );
    }
}
