//! The viewer's static files, embedded in the binary so `vesselcad serve` needs
//! nothing beside it: the page, its script and style, and the three.js bundle
//! (three.js r187 with GLTFLoader and OrbitControls, MIT, built from npm by
//! `viewer/` with esbuild and committed with its licence header), and the
//! design format's JSON Schema, from which the viewer types its editors, and
//! `tiles.js`, which shows a `build --tiles` tileset by level of detail in a
//! three.js page of one's own.
//!
//! Files are looked up by exact name in a fixed table, never on the file system,
//! so no request path (`..`, `%2e%2e`, absolute paths, symlinks) can reach a file
//! outside this folder.

/// One embedded file.
#[derive(Debug, Clone, Copy)]
pub struct Asset {
    /// The `Content-Type` it is served with.
    pub content_type: &'static str,
    /// Its bytes.
    pub bytes: &'static [u8],
}

/// The viewer page, served at `/`.
pub const INDEX: Asset = Asset {
    content_type: "text/html; charset=utf-8",
    bytes: include_bytes!("assets/index.html"),
};

/// The files served under `/static/`, by name.
const STATIC: &[(&str, Asset)] = &[
    (
        "viewer.js",
        Asset {
            content_type: "text/javascript; charset=utf-8",
            bytes: include_bytes!("assets/viewer.js"),
        },
    ),
    (
        "tiles.js",
        Asset {
            content_type: "text/javascript; charset=utf-8",
            bytes: include_bytes!("assets/tiles.js"),
        },
    ),
    (
        "viewer.css",
        Asset {
            content_type: "text/css; charset=utf-8",
            bytes: include_bytes!("assets/viewer.css"),
        },
    ),
    (
        "schema.json",
        Asset {
            content_type: "application/schema+json",
            bytes: include_bytes!("../../docs/vesselcad-1.schema.json"),
        },
    ),
    (
        "three-bundle.js",
        Asset {
            content_type: "text/javascript; charset=utf-8",
            bytes: include_bytes!("assets/three-bundle.js"),
        },
    ),
];

/// The static file called `name` (the request path after `/static/`), if any.
pub fn lookup(name: &str) -> Option<Asset> {
    STATIC.iter().find(|(n, _)| *n == name).map(|(_, a)| *a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_listed_names_resolve() {
        assert!(lookup("viewer.js").is_some());
        for name in [
            "../viewer.js",
            "./viewer.js",
            "/viewer.js",
            "assets/viewer.js",
            "",
            "..",
        ] {
            assert!(lookup(name).is_none(), "{name}");
        }
    }
}
