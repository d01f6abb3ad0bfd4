//! A table of shared values in use, by a 128-bit content key, holding weak
//! references: an entry lives as long as something else keeps its value.
//!
//! The Tessellate stage's meshes in use ([`MeshInstances`](super::MeshInstances))
//! and the Geometry stage's canonical cuts ([`SharedCuts`](crate::mesh::SharedCuts))
//! are such tables: a patch (an opening) equal by key to one already built takes
//! the value in use instead of building it again, and the table never keeps a
//! value alive on its own.

use std::sync::{Arc, Weak};

use rustc_hash::FxHashMap;

/// Shared values in use by key, held weakly (dead entries are swept as the
/// table grows).
#[derive(Debug)]
pub struct WeakTable<T> {
    table: FxHashMap<u128, Weak<T>>,
    /// Table size after the last sweep.
    swept: usize,
}

impl<T> Default for WeakTable<T> {
    fn default() -> Self {
        Self {
            table: FxHashMap::default(),
            swept: 0,
        }
    }
}

impl<T> WeakTable<T> {
    /// The value in use for `key`, if something still keeps it.
    pub fn get(&self, key: u128) -> Option<Arc<T>> {
        self.table.get(&key)?.upgrade()
    }

    /// Records `value` as the value of `key`.
    pub fn insert(&mut self, key: u128, value: &Arc<T>) {
        self.table.insert(key, Arc::downgrade(value));
        if self.table.len() > 2 * self.swept + 1024 {
            self.table.retain(|_, v| v.strong_count() > 0);
            self.swept = self.table.len();
        }
    }

    /// Entries (some possibly dead until the next sweep).
    pub fn len(&self) -> usize {
        self.table.len()
    }

    /// Whether the table is empty.
    pub fn is_empty(&self) -> bool {
        self.table.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_entry_lives_as_long_as_its_value_is_kept() {
        let mut t = WeakTable::default();
        let kept = Arc::new(7u32);
        t.insert(1, &kept);
        t.insert(2, &Arc::new(8u32));
        assert_eq!(t.get(1).as_deref(), Some(&7));
        assert_eq!(t.get(2), None, "nothing keeps the second value");
        assert_eq!(t.get(3), None);
        drop(kept);
        assert_eq!(t.get(1), None);
    }

    #[test]
    fn dead_entries_are_swept_as_the_table_grows() {
        let mut t = WeakTable::default();
        let kept: Vec<Arc<u64>> = (0..10).map(Arc::new).collect();
        for (k, v) in kept.iter().enumerate() {
            t.insert(k as u128, v);
        }
        for k in 10..5000u128 {
            t.insert(k, &Arc::new(0u64));
        }
        assert!(t.len() < 2100, "swept: {} entries", t.len());
        assert!((0..10).all(|k| t.get(k).is_some()));
    }
}
