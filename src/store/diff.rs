//! Differences between two designs: the JSON Patch (RFC 6902) that turns one
//! into the other, and the same as a list an engineer reads — each changed
//! parameter named by vessel tag, part id, nozzle mark or note id rather than by
//! array index (`V-101 shell S1 length: 7200 → 8000`).

use serde::Serialize;
use serde_json::Value;

use super::snapshot::{design_value, patch_between};
use crate::design::Design;

/// One changed parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Changed {
    /// Where, readable (`V-101 nozzle N1 size`).
    pub place: String,
    /// The JSON path (`/vessels/0/nozzles/0/size`).
    pub path: String,
    /// The value before (absent when added).
    pub before: Option<Value>,
    /// The value after (absent when removed).
    pub after: Option<Value>,
}

impl std::fmt::Display for Changed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (&self.before, &self.after) {
            (Some(b), Some(a)) => write!(f, "{}: {} → {}", self.place, short(b), short(a)),
            (None, Some(a)) => write!(f, "{}: added {}", self.place, short(a)),
            (Some(b), None) => write!(f, "{}: removed (was {})", self.place, short(b)),
            (None, None) => write!(f, "{}", self.place),
        }
    }
}

/// A value as compact JSON, cut at 80 characters.
fn short(value: &Value) -> String {
    let text = value.to_string();
    if text.chars().count() <= 80 {
        return text;
    }
    let cut: String = text.chars().take(77).collect();
    format!("{cut}...")
}

/// The difference from `before` to `after`: the patch and the readable list.
pub fn diff(before: &Design, after: &Design) -> (Value, Vec<Changed>) {
    let patch = patch_between(before, after);
    let old = design_value(before);
    let new = design_value(after);
    let changes = patch
        .as_array()
        .map(|ops| {
            ops.iter()
                .map(|op| {
                    let path = op["path"].as_str().unwrap_or_default().to_string();
                    let kind = op["op"].as_str().unwrap_or_default();
                    let before = (kind != "add")
                        .then(|| old.pointer(&path).cloned())
                        .flatten();
                    let after = (kind != "remove").then(|| op["value"].clone());
                    let named = if kind == "add" { &new } else { &old };
                    Changed {
                        place: place(named, &path),
                        path,
                        before,
                        after,
                    }
                })
                .collect()
        })
        .unwrap_or_default();
    (patch, changes)
}

/// The readable name of a JSON path in `doc`.
fn place(doc: &Value, path: &str) -> String {
    let mut words: Vec<String> = Vec::new();
    let mut node = doc;
    let segments: Vec<String> = path
        .split('/')
        .skip(1)
        .map(|s| s.replace("~1", "/").replace("~0", "~"))
        .collect();
    let mut k = 0;
    while k < segments.len() {
        let segment = &segments[k];
        let child = match node {
            Value::Object(map) => map.get(segment),
            Value::Array(items) => segment.parse::<usize>().ok().and_then(|i| items.get(i)),
            _ => None,
        };
        let Some(child) = child else {
            words.push(segment.clone());
            k += 1;
            continue;
        };
        match (segment.as_str(), child) {
            ("vessels" | "parts" | "nozzles" | "notes", Value::Array(items))
                if k + 1 < segments.len() =>
            {
                let index = segments[k + 1].parse::<usize>().ok();
                let item = index.and_then(|i| items.get(i));
                words.push(match (segment.as_str(), item) {
                    ("vessels", Some(v)) => name_or(v, "tag", &segments[k + 1]),
                    ("parts", Some(Value::Object(p))) => match p.iter().next() {
                        Some((kind, body)) => format!("{kind} {}", name_or(body, "id", "?")),
                        None => format!("part {}", segments[k + 1]),
                    },
                    ("nozzles", Some(n)) => format!("nozzle {}", name_or(n, "mark", "?")),
                    ("notes", Some(n)) => format!("note {}", name_or(n, "id", "?")),
                    (what, _) => format!("{what} {}", segments[k + 1]),
                });
                node = match (segment.as_str(), item) {
                    // A part's kind key is named with its id already.
                    ("parts", Some(Value::Object(p))) if k + 2 < segments.len() => {
                        k += 1;
                        p.values().next().unwrap_or(&Value::Null)
                    }
                    (_, Some(item)) => item,
                    _ => &Value::Null,
                };
                k += 2;
            }
            _ => {
                words.push(segment.clone());
                node = child;
                k += 1;
            }
        }
    }
    if words.is_empty() {
        "the whole design".into()
    } else {
        words.join(" ")
    }
}

fn name_or(value: &Value, key: &str, fallback: &str) -> String {
    value[key].as_str().unwrap_or(fallback).to_string()
}
