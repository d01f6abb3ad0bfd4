//! Whole-design checks: unique vessel tags, then every vessel's rules through the
//! constraint resolver. All violations are collected, not only the first.

use std::collections::HashMap;

use crate::constraints::{ResolvedVessel, resolve_vessel};
use crate::format::error::{DesignError, RuleViolation};
use crate::format::schema::Design;

/// Resolves every vessel of a design; `Err` lists every broken rule.
pub fn resolve(design: &Design) -> Result<Vec<ResolvedVessel>, DesignError> {
    let mut violations = Vec::new();
    let mut tags: HashMap<&str, usize> = HashMap::new();
    for (i, v) in design.vessels.iter().enumerate() {
        if let Some(first) = tags.insert(&v.tag, i) {
            violations.push(RuleViolation {
                path: format!("vessels[{i}].tag"),
                entity: v.tag.clone(),
                field: "tag".into(),
                value: v.tag.clone(),
                rule: format!("duplicate tag: already used by vessels[{first}]"),
            });
        }
    }
    let mut resolved = Vec::with_capacity(design.vessels.len());
    for (i, v) in design.vessels.iter().enumerate() {
        match resolve_vessel(v, i) {
            Ok(r) => resolved.push(r),
            Err(mut e) => violations.append(&mut e),
        }
    }
    if violations.is_empty() {
        Ok(resolved)
    } else {
        Err(DesignError::Invalid(violations))
    }
}

/// Checks every rule of a design.
pub fn validate(design: &Design) -> Result<(), DesignError> {
    resolve(design).map(|_| ())
}
