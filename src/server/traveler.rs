//! `GET /traveler.html?vessel=TAG` and `GET /traveler.csv?vessel=TAG`: the shop
//! traveler of one vessel of the live design (`fab::process_plan` with the
//! built-in shop rules), made on request from the session's current design.

use axum::extract::{Query, State};
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::error::ApiError;
use super::state::AppState;
use crate::design::resolve;
use crate::fab::traveler::{traveler_csv, traveler_html};
use crate::fab::{ShopRules, process_plan};

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
            let resolved = resolve(&design).map_err(|e| ApiError::Plan(e.to_string()))?;
            let plan = process_plan(
                &design.vessels[index],
                &resolved[index],
                &ShopRules::builtin(),
            )
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
