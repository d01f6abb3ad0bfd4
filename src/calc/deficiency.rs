//! Which part or nozzle each deficiency of a calculation is about, so a viewer
//! can colour the part and show its figures. Every deficiency sentence of
//! [`super::Calculation`] begins with the id of its part or the mark of its
//! nozzle, followed by `:` or a space (`S1: course …`, `N2: UG-37 …`,
//! `SK at the base …`, `SD1 (hydrotest): …`); a sentence that names none of the
//! vessel's ids is the vessel's own.

use serde::Serialize;

use super::Calculation;
use crate::design::VesselDesign;

/// One deficiency with the item it is about.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Deficiency {
    /// The stable id of the item: `tag/id` for a part, `tag/mark` for a
    /// nozzle, `tag` for the vessel as a whole.
    pub id: String,
    /// The sentence, with its figures and rule.
    pub text: String,
}

/// The deficiencies of `calc`, the calculation of vessel `design`, each with its
/// item's stable id (the longest of the vessel's part ids and nozzle marks
/// that begins the sentence).
pub fn deficiencies_by_item(design: &VesselDesign, calc: &Calculation) -> Vec<Deficiency> {
    let ids: Vec<&str> = design
        .parts
        .iter()
        .map(|p| p.id())
        .chain(design.nozzles.iter().map(|n| n.mark.as_str()))
        .collect();
    calc.vessel
        .deficiencies
        .iter()
        .map(|text| {
            let item = ids
                .iter()
                .filter(|id| {
                    text.strip_prefix(**id)
                        .is_some_and(|rest| rest.starts_with(':') || rest.starts_with(' '))
                })
                .max_by_key(|id| id.len());
            Deficiency {
                id: match item {
                    Some(id) => format!("{}/{id}", design.tag),
                    None => design.tag.clone(),
                },
                text: text.clone(),
            }
        })
        .collect()
}
