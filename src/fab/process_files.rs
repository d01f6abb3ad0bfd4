//! Writes a process plan's files into a directory: the traveler (HTML, CSV),
//! the BOM (CSV), the weld map (CSV, JSON, GLB of coloured lines, SVG sheet)
//! and the whole plan as JSON (`vesselcad-process/1`), each named by the
//! vessel tag (`V-101-traveler.html`, …).

use std::path::{Path, PathBuf};

use glam::DAffine3;
use serde_json::json;

use super::plan_error::PlanError;
use super::process::ProcessPlan;
use super::traveler::{bom_csv, traveler_csv, traveler_html, welds_csv};
use super::weld_glb::weld_glb;
use super::weld_svg::weld_svg;

/// The format tag of the plan's JSON.
pub const PROCESS_FORMAT: &str = "vesselcad-process/1";

/// The plan as JSON.
pub fn plan_json(plan: &ProcessPlan, source: &str) -> serde_json::Value {
    json!({
        "format": PROCESS_FORMAT,
        "file": source,
        "units": {"length": "mm", "mass": "kg", "area": "m2", "volume": "mm3"},
        "plan": plan,
    })
}

/// Writes every file of `plan` into `dir` (created if missing); `frame` maps
/// the vessel frame into the plant frame (for the GLB). Returns the paths
/// written.
///
/// # Errors
///
/// [`PlanError::Io`] naming the file that cannot be written.
pub fn write_process_files(
    plan: &ProcessPlan,
    frame: DAffine3,
    source: &str,
    dir: &Path,
) -> Result<Vec<PathBuf>, PlanError> {
    let io = |path: &Path, e: std::io::Error| PlanError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let tag = &plan.vessel;
    let welds_json = serde_json::to_string_pretty(&json!({
        "format": PROCESS_FORMAT,
        "vessel": tag,
        "welds": plan.welds,
    }))
    .unwrap_or_default();
    let files: Vec<(String, Vec<u8>)> = vec![
        (
            format!("{tag}-traveler.html"),
            traveler_html(plan, source).into_bytes(),
        ),
        (
            format!("{tag}-traveler.csv"),
            traveler_csv(plan).into_bytes(),
        ),
        (format!("{tag}-bom.csv"), bom_csv(plan).into_bytes()),
        (format!("{tag}-welds.csv"), welds_csv(plan).into_bytes()),
        (format!("{tag}-welds.json"), welds_json.into_bytes()),
        (
            format!("{tag}-welds.glb"),
            weld_glb(plan, frame).map_err(|e| PlanError::Io {
                path: dir.join(format!("{tag}-welds.glb")).display().to_string(),
                message: e.to_string(),
            })?,
        ),
        (format!("{tag}-weld-map.svg"), weld_svg(plan).into_bytes()),
        (
            format!("{tag}-process.json"),
            serde_json::to_string_pretty(&plan_json(plan, source))
                .unwrap_or_default()
                .into_bytes(),
        ),
    ];
    let mut written = Vec::new();
    for (name, bytes) in files {
        let path = dir.join(name);
        std::fs::write(&path, bytes).map_err(|e| io(&path, e))?;
        written.push(path);
    }
    Ok(written)
}
