//! `GET /traveler.html?vessel=TAG` and `GET /traveler.csv?vessel=TAG`: the shop
//! traveler of one vessel of the live design (`fab::process_plan` with the
//! built-in shop rules), made on request from the session's current design;
//! `GET /plates.json?vessel=TAG` lists its plates (id, DXF file, kind, part,
//! thickness, outline size): the courses', cones' and skirts' plates, the
//! boots' plates and the head blanks; `GET /plates/<file>?vessel=TAG`
//! serves one of them as the 1:1 mm DXF `vesselcad fab` writes
//! (`fab::plate_dxf`, `fab::boot`, `fab::blank_dxf`).

use axum::extract::{Query, State};
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::error::ApiError;
use super::state::AppState;
use crate::fab::blank_dxf::{blank_drawing, blank_id};
use crate::fab::boot::boot_drawing;
use crate::fab::openings::FormedOpening;
use crate::fab::traveler::{traveler_csv, traveler_html};
use crate::fab::{FabPlan, ShopRules, plan_process};

/// The query of the traveler routes.
#[derive(Deserialize)]
pub struct TravelerQuery {
    /// Vessel tag.
    vessel: Option<String>,
}

/// The traveler's two formats.
#[derive(Clone, Copy)]
enum Format {
    Html,
    Csv,
}

async fn traveler(
    state: AppState,
    query: Result<Query<TravelerQuery>, axum::extract::rejection::QueryRejection>,
    format: Format,
) -> Result<Response, ApiError> {
    let route = match format {
        Format::Html => "/traveler.html",
        Format::Csv => "/traveler.csv",
    };
    let Ok(Query(TravelerQuery { vessel: Some(tag) })) = query else {
        return Err(ApiError::BadQuery(format!("expected {route}?vessel=<tag>")));
    };
    let body = state
        .with_session(move |s, _| {
            let design = s.model().design();
            let Some(index) = design.vessels.iter().position(|v| v.tag == tag) else {
                return Err(ApiError::UnknownVessel {
                    tag,
                    known: design.vessels.iter().map(|v| v.tag.clone()).collect(),
                });
            };
            let tag = &design.vessels[index].tag;
            let (_, plan) = plan_process(&design, tag, &ShopRules::builtin())
                .map_err(|e| ApiError::Plan(e.to_string()))?;
            Ok(match format {
                Format::Html => traveler_html(&plan, "live design"),
                Format::Csv => traveler_csv(&plan),
            })
        })
        .await?;
    let content_type = match format {
        Format::Html => "text/html; charset=utf-8",
        Format::Csv => "text/csv; charset=utf-8",
    };
    Ok((
        [(header::CONTENT_TYPE, HeaderValue::from_static(content_type))],
        body,
    )
        .into_response())
}

/// The plate layout of the vessel queried, from the session's design.
async fn fab_plan_of(
    state: &AppState,
    route: &'static str,
    query: Result<Query<TravelerQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<crate::fab::FabPlan, ApiError> {
    let Ok(Query(TravelerQuery { vessel: Some(tag) })) = query else {
        return Err(ApiError::BadQuery(format!("expected {route}?vessel=<tag>")));
    };
    state
        .with_session(move |s, _| {
            let design = s.model().design();
            if !design.vessels.iter().any(|v| v.tag == tag) {
                return Err(ApiError::UnknownVessel {
                    tag,
                    known: design.vessels.iter().map(|v| v.tag.clone()).collect(),
                });
            }
            crate::fab::plan(&design, &tag, &ShopRules::builtin().plates)
                .map_err(|e| ApiError::Plan(e.to_string()))
        })
        .await
}

/// `GET /plates.json?vessel=TAG`: the vessel's plates.
pub async fn plate_list(
    State(state): State<AppState>,
    query: Result<Query<TravelerQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let plan = fab_plan_of(&state, "/plates.json", query).await?;
    let mut plates: Vec<_> = plan
        .plates
        .iter()
        .map(|p| {
            let (w, h) = p.outline.extent();
            serde_json::json!({
                "id": p.id,
                "file": p.file_name(),
                "kind": "plate",
                "part": p.part,
                "course": p.course,
                "thickness": p.thickness,
                "size": [w, h],
                "openings": p.openings.iter().map(|o| o.mark.clone()).collect::<Vec<_>>(),
            })
        })
        .collect();
    plates.extend(plan.boot_plates().iter().map(|p| {
        let (w, h) = p.extent();
        serde_json::json!({
            "id": p.id,
            "file": p.file_name(),
            "kind": "boot plate",
            "part": p.part,
            "thickness": p.thickness,
            "size": [w, h],
            "openings": [],
        })
    }));
    plates.extend(plan.blanks().map(|b| {
        let id = blank_id(&plan.tag, b);
        serde_json::json!({
            "file": format!("{id}.dxf"),
            "id": id,
            "kind": "head blank",
            "part": b.id,
            "thickness": b.thickness,
            "size": [b.diameter, b.diameter],
            "openings": formed_on(&plan, &b.id).iter().map(|f| f.mark.clone()).collect::<Vec<_>>(),
        })
    }));
    Ok(axum::Json(serde_json::json!({ "vessel": plan.tag, "plates": plates })).into_response())
}

/// `GET /plates/<plate id>.dxf?vessel=TAG`: one plate's cutting DXF.
pub async fn plate_dxf(
    State(state): State<AppState>,
    axum::extract::Path(file): axum::extract::Path<String>,
    query: Result<Query<TravelerQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let plan = fab_plan_of(&state, "/plates/<plate id>.dxf", query).await?;
    let bytes = plate_file(&plan, &file)?;
    let disposition = format!("attachment; filename=\"{}\"", file.replace('"', "_"));
    Ok((
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("image/vnd.dxf"),
            ),
            (
                header::CONTENT_DISPOSITION,
                HeaderValue::from_str(&disposition)
                    .unwrap_or(HeaderValue::from_static("attachment")),
            ),
        ],
        bytes,
    )
        .into_response())
}

/// `GET /traveler.html?vessel=TAG`.
pub async fn traveler_page(
    State(state): State<AppState>,
    query: Result<Query<TravelerQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    traveler(state, query, Format::Html).await
}

/// `GET /traveler.csv?vessel=TAG`.
pub async fn traveler_table(
    State(state): State<AppState>,
    query: Result<Query<TravelerQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    traveler(state, query, Format::Csv).await
}

/// The openings marked on the head blank of part `head`.
fn formed_on<'a>(plan: &'a FabPlan, head: &str) -> Vec<&'a FormedOpening> {
    plan.openings
        .formed
        .iter()
        .filter(|f| f.host == head)
        .collect()
}

/// The DXF named `file` of the vessel's plates, boot plates and head blanks.
fn plate_file(plan: &FabPlan, file: &str) -> Result<Vec<u8>, ApiError> {
    let drawing = if let Some(plate) = plan.plates.iter().find(|p| p.file_name() == file) {
        let course = &plan.seams.courses[plate.course_index];
        let rolled = &plan.developments.rolled[course.rolled];
        crate::fab::plate_dxf::plate_drawing(plate, &plan.grade, rolled, course)
    } else if let Some(plate) = plan.boot_plates().iter().find(|p| p.file_name() == file) {
        boot_drawing(plate, &plan.grade)
    } else if let Some(blank) = plan
        .blanks()
        .find(|b| format!("{}.dxf", blank_id(&plan.tag, b)) == file)
    {
        blank_drawing(&plan.tag, blank, &plan.grade, &formed_on(plan, &blank.id))
    } else {
        let known: Vec<String> = plan
            .plates
            .iter()
            .map(|p| p.file_name())
            .chain(plan.boot_plates().iter().map(|p| p.file_name()))
            .chain(
                plan.blanks()
                    .map(|b| format!("{}.dxf", blank_id(&plan.tag, b))),
            )
            .collect();
        return Err(ApiError::NotFound(format!(
            "/plates/{file}: vessel {} has the plates {}",
            plan.tag,
            known.join(", ")
        )));
    };
    let mut bytes = Vec::new();
    drawing
        .save(&mut bytes)
        .map_err(|e| ApiError::Plan(format!("{file}: {e}")))?;
    Ok(bytes)
}
