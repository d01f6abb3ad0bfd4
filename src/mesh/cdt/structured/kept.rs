//! Cavity triangulations kept from one meshing of a patch for the next.
//!
//! An edit that moves one opening of a course meshes the whole course again,
//! yet every other opening's cavity comes out with the very same loops: the
//! lattice's rows do not depend on the holes, and an opening that did not move
//! keeps its cut bit for bit. `cavity::fill` looks each cavity up here by its
//! exact inputs — the (u, v) of its boundary and hole vertices, where each hole
//! starts, and the size metric at its centre, all bit for bit — and takes the
//! triangles found for them last time instead of zipping or sweeping again.
//! Those triangles are a deterministic function of exactly these inputs, so the
//! mesh is the one a fresh meshing gives. The Tessellate stage keeps each
//! patch's [`KeptCavities`] beside its mesh and hands it to the next meshing of
//! that patch, which returns the cavities it met.
//!
//! A kept cavity also carries the screen's verdicts on its triangles, with the
//! key of the surface, analytic surface and options they were found on
//! ([`Memo::surface`]). On a course every probe goes through one row evaluator,
//! so a triangle's verdict is a function of its vertices, the surface and the
//! options alone; a later meshing on the same key takes the verdicts instead of
//! screening the cavity again (`rings`). Other surfaces screen afresh.

use std::hash::{Hash, Hasher};
use std::sync::{Arc, OnceLock};

use glam::DVec2;
use rustc_hash::{FxHashMap, FxHasher};

use super::cavity_fill::Triangle;
use crate::mesh::cdt::metric::Metric;
use crate::mesh::cdt::plan::CAVITY_FILLS;

/// The cavities met by one meshing of a patch (shared with the meshings that
/// met them before).
#[derive(Debug, Default)]
pub struct KeptCavities {
    cavities: Vec<Arc<Kept>>,
    /// Hash of the inputs → index into `cavities` (of the first with that hash).
    by_hash: FxHashMap<u64, u32>,
}

/// One cavity's inputs and its triangles in the cavity's local numbering (its
/// boundary's vertices, then each hole's), with the screen's verdicts on them.
#[derive(Debug)]
pub(in crate::mesh::cdt) struct Kept {
    input: CavityInput,
    triangles: Box<[Triangle]>,
    /// The screen's verdict on each triangle and the key of the surface, the
    /// analytic surface and the options it screened against
    /// ([`Memo::surface`]), once screened.
    verdicts: OnceLock<(u128, Box<[bool]>)>,
}

impl Kept {
    pub fn new(input: CavityInput, triangles: Vec<Triangle>) -> Arc<Self> {
        Arc::new(Self {
            input,
            triangles: triangles.into_boxed_slice(),
            verdicts: OnceLock::new(),
        })
    }

    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// The screen's verdicts on the triangles, when they were screened on the
    /// surface with key `surface`.
    pub fn verdicts(&self, surface: u128) -> Option<&[bool]> {
        self.verdicts
            .get()
            .filter(|(key, v)| *key == surface && v.len() == self.triangles.len())
            .map(|(_, v)| &**v)
    }

    /// This cavity with `verdicts` screened on the surface with key `surface`
    /// recorded: itself unless it holds another surface's, then a copy.
    pub fn with_verdicts(self: &Arc<Self>, surface: u128, verdicts: &[bool]) -> Arc<Self> {
        let _ = self.verdicts.set((surface, verdicts.into()));
        if self.verdicts(surface).is_some() {
            return self.clone();
        }
        Arc::new(Self {
            input: self.input.clone(),
            triangles: self.triangles.clone(),
            verdicts: OnceLock::from((surface, Box::from(verdicts))),
        })
    }
}

/// What a cavity's triangulation is a function of: its loops' (u, v), boundary
/// first, where each hole starts in that list, and the size metric at its
/// centre.
#[derive(Clone, Debug, PartialEq)]
pub(in crate::mesh::cdt) struct CavityInput {
    uvs: Box<[DVec2]>,
    starts: Box<[u32]>,
    metric: [f64; 3],
    hash: u64,
}

impl CavityInput {
    pub fn new(uvs: Vec<DVec2>, starts: Vec<u32>, metric: &Metric) -> Self {
        let metric = [metric.uu, metric.uv, metric.vv];
        let mut h = FxHasher::default();
        for p in &uvs {
            p.x.to_bits().hash(&mut h);
            p.y.to_bits().hash(&mut h);
        }
        starts.hash(&mut h);
        metric.map(f64::to_bits).hash(&mut h);
        Self {
            uvs: uvs.into_boxed_slice(),
            starts: starts.into_boxed_slice(),
            metric,
            hash: h.finish(),
        }
    }

    /// Whether the two are the same bit for bit (`==` on the floats would also
    /// match 0.0 with -0.0).
    fn same(&self, other: &CavityInput) -> bool {
        let bits = |p: &DVec2| (p.x.to_bits(), p.y.to_bits());
        self.hash == other.hash
            && self.starts == other.starts
            && self.metric.map(f64::to_bits) == other.metric.map(f64::to_bits)
            && self.uvs.len() == other.uvs.len()
            && self
                .uvs
                .iter()
                .zip(&*other.uvs)
                .all(|(a, b)| bits(a) == bits(b))
    }
}

impl KeptCavities {
    /// The cavities `found`.
    pub(in crate::mesh::cdt) fn new(cavities: Vec<Arc<Kept>>) -> Self {
        let mut by_hash = FxHashMap::default();
        for (i, kept) in cavities.iter().enumerate() {
            by_hash.entry(kept.input.hash).or_insert(i as u32);
        }
        Self { cavities, by_hash }
    }

    /// The cavity kept with exactly these inputs.
    pub(in crate::mesh::cdt) fn find(&self, input: &CavityInput) -> Option<&Arc<Kept>> {
        let kept = &self.cavities[*self.by_hash.get(&input.hash)? as usize];
        kept.input.same(input).then_some(kept)
    }

    /// Cavities kept.
    pub fn len(&self) -> usize {
        self.cavities.len()
    }

    /// Whether none is kept.
    pub fn is_empty(&self) -> bool {
        self.cavities.is_empty()
    }

    /// Heap bytes held (for the model's memory report; a cavity shared with
    /// another patch's memo counts in both).
    pub fn heap_bytes(&self) -> usize {
        let each = |k: &Arc<Kept>| {
            std::mem::size_of::<Kept>()
                + k.input.uvs.len() * std::mem::size_of::<DVec2>()
                + k.input.starts.len() * 4
                + k.triangles.len() * std::mem::size_of::<Triangle>()
                + k.verdicts.get().map_or(0, |(_, v)| v.len())
        };
        self.cavities.iter().map(each).sum::<usize>() + self.by_hash.capacity() * 16
    }
}

/// The kept cavities a meshing may take from and the ones it meets, handed
/// down to `cavity::fill`.
#[derive(Default)]
pub(in crate::mesh::cdt) struct Memo<'k> {
    pub kept: Option<&'k KeptCavities>,
    /// The key of the surface, its analytic surface and the options
    /// (`mesh::surface_key`): kept cavities' screen verdicts are
    /// taken when recorded on the same key. `None`: none taken or recorded.
    pub surface: Option<u128>,
    /// Whether the cavities met are wanted (a caller that keeps none does not
    /// pay for recording them).
    pub record: bool,
    pub found: Vec<Arc<Kept>>,
    /// Cavities whose triangles were taken from `kept`.
    pub reused: usize,
    /// Cavities filled, by fill (indexed as `plan::CAVITY_FILLS`).
    pub fills: [usize; CAVITY_FILLS.len()],
}

impl<'k> Memo<'k> {
    pub fn new(kept: Option<&'k KeptCavities>, record: bool) -> Self {
        Self {
            kept,
            surface: None,
            record,
            found: Vec::new(),
            reused: 0,
            fills: [0; CAVITY_FILLS.len()],
        }
    }

    /// This memo, taking and recording screen verdicts on the surface with key
    /// `surface` (see [`Memo::surface`]).
    pub fn on_surface(self, surface: u128) -> Self {
        Self {
            surface: Some(surface),
            ..self
        }
    }

    /// The cavities met, to keep.
    pub fn into_kept(self) -> KeptCavities {
        KeptCavities::new(self.found)
    }

    /// Forgets what a meshing attempt met (its result was not taken).
    pub fn restart(&mut self) {
        self.found.clear();
        self.reused = 0;
        self.fills = [0; CAVITY_FILLS.len()];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const METRIC: Metric = Metric {
        uu: 4.0,
        uv: 0.0,
        vv: 1.0,
    };

    fn input(shift: f64) -> CavityInput {
        let uvs = (0..8)
            .map(|k| DVec2::new(0.1 * k as f64 + shift, 0.5))
            .collect();
        CavityInput::new(uvs, vec![4], &METRIC)
    }

    #[test]
    fn a_cavity_is_found_only_with_inputs_equal_bit_for_bit() {
        let tris: Vec<Triangle> = vec![([0, 1, 4], [false, false, true])];
        let kept = KeptCavities::new(vec![Kept::new(input(0.0), tris.clone())]);
        assert_eq!(
            kept.find(&input(0.0)).map(|k| k.triangles()),
            Some(&tris[..])
        );
        // The smallest change of one coordinate, of the metric or of where the
        // hole starts misses.
        assert!(kept.find(&input(1e-300)).is_none());
        let mut uvs: Vec<DVec2> = input(0.0).uvs.into_vec();
        uvs[3].y = f64::from_bits(uvs[3].y.to_bits() + 1);
        assert!(
            kept.find(&CavityInput::new(uvs, vec![4], &METRIC))
                .is_none()
        );
        let other = Metric { uv: -0.0, ..METRIC };
        let same_uvs = input(0.0).uvs.into_vec();
        assert!(
            kept.find(&CavityInput::new(same_uvs.clone(), vec![4], &other))
                .is_none()
        );
        assert!(
            kept.find(&CavityInput::new(same_uvs, vec![5], &METRIC))
                .is_none()
        );
        assert!(kept.heap_bytes() > 8 * 16);
    }

    #[test]
    fn verdicts_are_taken_only_on_the_surface_they_were_screened_on() {
        let tris: Vec<Triangle> = vec![([0, 1, 4], [false; 3]), ([1, 2, 4], [false; 3])];
        let kept = Kept::new(input(0.0), tris);
        assert_eq!(kept.verdicts(7), None);
        // Recorded in place the first time, and found again on that surface only.
        let same = kept.with_verdicts(7, &[true, false]);
        assert!(Arc::ptr_eq(&same, &kept));
        assert_eq!(kept.verdicts(7), Some(&[true, false][..]));
        assert_eq!(kept.verdicts(8), None);
        // Another surface's verdicts go to a copy; the original keeps its own.
        let other = kept.with_verdicts(8, &[false, false]);
        assert!(!Arc::ptr_eq(&other, &kept));
        assert_eq!(other.verdicts(8), Some(&[false, false][..]));
        assert_eq!(other.triangles(), kept.triangles());
        assert_eq!(kept.verdicts(7), Some(&[true, false][..]));
        // Verdicts that do not match the triangles are never handed out.
        let short = Kept::new(input(0.0), vec![([0, 1, 4], [false; 3])]);
        let short = short.with_verdicts(7, &[true, true]);
        assert_eq!(short.verdicts(7), None);
    }
}
