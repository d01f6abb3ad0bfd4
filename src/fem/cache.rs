//! The FE mesh pieces ([`super::piece`]) of the vessels meshed so far, each
//! with the key it was meshed from: a build meshes the pieces whose key
//! differs from the one held (in parallel) and takes the others as they are,
//! as the render meshes are kept by content. [`FemCounters`] say which.

use std::collections::HashMap;
use std::sync::Arc;

use rayon::prelude::*;

use super::envelope::Plan;
use super::piece::{self, Piece, PieceKey};

/// What the last build through a [`FemCache`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FemCounters {
    /// Pieces meshed (their key was new or had changed).
    pub meshed: usize,
    /// Pieces taken from the cache unchanged.
    pub reused: usize,
    /// Names (part ids) of the pieces meshed, in the mesh's order.
    pub meshed_pieces: Vec<String>,
}

/// Meshed pieces by vessel tag and piece name, with their keys.
#[derive(Debug, Default)]
pub struct FemCache {
    pieces: HashMap<(String, String), (PieceKey, Arc<Piece>)>,
    counters: FemCounters,
}

impl FemCache {
    /// An empty cache.
    pub fn new() -> FemCache {
        FemCache::default()
    }

    /// What the last build did.
    pub fn counters(&self) -> &FemCounters {
        &self.counters
    }

    /// The piece named `name` (a part id) of vessel `tag`, as last built.
    pub fn piece(&self, tag: &str, name: &str) -> Option<Arc<Piece>> {
        self.pieces
            .get(&(tag.to_owned(), name.to_owned()))
            .map(|(_, p)| Arc::clone(p))
    }

    /// The pieces of `plan` (keys `inputs`), in order: held ones whose key is
    /// unchanged, the others meshed now. The vessel's pieces not among
    /// `inputs` are dropped.
    pub fn pieces(&mut self, plan: &Plan, inputs: Vec<(String, PieceKey)>) -> Vec<Arc<Piece>> {
        let tag = plan.tag.clone();
        let held: Vec<Option<Arc<Piece>>> = inputs
            .iter()
            .map(|(name, key)| {
                self.pieces
                    .get(&(tag.clone(), name.clone()))
                    .filter(|(k, _)| k == key)
                    .map(|(_, p)| Arc::clone(p))
            })
            .collect();
        let built: Vec<(Arc<Piece>, bool)> = inputs
            .par_iter()
            .zip(held)
            .map(|((_, key), held)| match held {
                Some(p) => (p, false),
                None => (Arc::new(piece::mesh(key, &plan.mer)), true),
            })
            .collect();
        let mut counters = FemCounters::default();
        self.pieces
            .retain(|(t, name), _| *t != tag || inputs.iter().any(|(n, _)| n == name));
        let mut out = Vec::with_capacity(inputs.len());
        for ((name, key), (piece, meshed)) in inputs.into_iter().zip(built) {
            if meshed {
                counters.meshed += 1;
                counters.meshed_pieces.push(name.clone());
                self.pieces
                    .insert((tag.clone(), name), (key, Arc::clone(&piece)));
            } else {
                counters.reused += 1;
            }
            out.push(piece);
        }
        self.counters = counters;
        out
    }
}
