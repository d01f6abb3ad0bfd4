//! `GET /calc.json`: the live calculation's deficiencies of every vessel, each
//! with the stable id of its part or nozzle (`calc::deficiencies_by_item`), so
//! the viewer paints a deficient part red and lists its figures. The figures
//! are the model's calculation components (`systems::update_calculations`), as
//! current as the revision the answer names; nothing is computed here.
//!
//! ```text
//! {"revision": 7, "deficiencies": [{"id": "V-101/M1", "text": "M1: neck wall …"}]}
//! ```

use axum::extract::State;
use axum::http::{HeaderValue, header};
use axum::response::{IntoResponse, Response};
use serde_json::json;

use super::state::AppState;
use crate::calc::deficiencies_by_item;

/// The deficiencies of the session's current model.
pub async fn calc_json(State(state): State<AppState>) -> Response {
    let body = state
        .with_session(|s, _| {
            let model = s.model();
            let design = model.design();
            let found: Vec<_> = design
                .vessels
                .iter()
                .filter_map(|v| Some((v, model.calculation(&v.tag)?)))
                .flat_map(|(v, c)| deficiencies_by_item(v, &c))
                .collect();
            json!({ "revision": s.revision(), "deficiencies": found }).to_string()
        })
        .await;
    (
        [(
            header::CONTENT_TYPE,
            HeaderValue::from_static("application/json"),
        )],
        body,
    )
        .into_response()
}
