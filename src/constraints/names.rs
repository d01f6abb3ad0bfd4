//! Limits on the names a design gives: vessel tags, part and note ids, nozzle
//! marks. They become node names, file names of sheets, keys of the viewer's
//! maps and parts of every error message, so an unbounded one (a 500 KB tag
//! made a 38 MB model file) costs everything that repeats it.

/// The most characters a tag, id or mark may have.
pub(crate) const MAX_NAME_CHARS: usize = 64;

/// Whether `name` is longer than [`MAX_NAME_CHARS`].
pub(crate) fn too_long(name: &str) -> bool {
    // Counting stops one past the limit: a huge name costs no more than a short one.
    name.chars().take(MAX_NAME_CHARS + 1).count() > MAX_NAME_CHARS
}

/// A name for an error message: itself when within the limit, else its start
/// and its length.
pub(crate) fn shown(name: &str) -> String {
    if too_long(name) {
        let start: String = name.chars().take(16).collect();
        format!("{start:?}… ({} characters)", name.chars().count())
    } else {
        name.to_string()
    }
}

/// The rule an overlong name breaks.
pub(crate) fn rule() -> String {
    format!("must be at most {MAX_NAME_CHARS} characters")
}
