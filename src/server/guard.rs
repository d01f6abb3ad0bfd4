//! What keeps other web pages from driving a session: every request passes
//! [`guard`] before it reaches a route, and every answer leaves with the
//! security headers.
//!
//! - **Host.** A server bound to a loopback address answers only requests whose
//!   `Host` is a loopback name (`localhost`, `*.localhost`, `127.0.0.1`, `[::1]`,
//!   any port): a page on another name that resolves to 127.0.0.1 (DNS
//!   rebinding) is refused. A server bound elsewhere (`--bind`) takes any name.
//! - **Origin.** A request a browser marks with an `Origin` must come from the
//!   served origin (`http://<Host>`): a cross-origin edit, save or WebSocket is
//!   refused, whatever its method.
//! - **Content type.** An edit must be `application/json` or
//!   `application/json-patch+json`, so no HTML form or "simple" cross-origin
//!   request can send one; a save has no body or a JSON one.
//! - **Token.** With `--token`, every route but the page shell (`/`,
//!   `/static/…`) needs it, as `Authorization: Bearer <token>` or, for what a
//!   browser cannot send headers with (the WebSocket, the drawing image), a
//!   `token` query parameter on a GET.
//! - **Headers.** `Content-Security-Policy` (own scripts, styles, images and
//!   sockets only; `frame-ancestors 'none'`), `X-Frame-Options: DENY`,
//!   `X-Content-Type-Options: nosniff`, `Referrer-Policy: no-referrer`.

use axum::extract::{Query, Request, State};
use axum::http::{HeaderMap, HeaderValue, Method, Uri, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use super::error::ApiError;
use super::state::AppState;

/// Checks a request against the rules above, then runs it and adds the
/// security headers to whatever it answers (refusals too).
pub async fn guard(State(state): State<AppState>, request: Request, next: Next) -> Response {
    let host = request
        .headers()
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .map(str::to_string);
    let mut response = match check(&state, &request, host.as_deref()) {
        Ok(()) => next.run(request).await,
        Err(e) => e.into_response(),
    };
    add_security_headers(response.headers_mut(), host.as_deref());
    response
}

/// The rules, in order: host, origin, content type, token.
fn check(state: &AppState, request: &Request, host: Option<&str>) -> Result<(), ApiError> {
    let headers = request.headers();
    let Some(host) = host else {
        return Err(ApiError::Forbidden("the request has no Host header".into()));
    };
    if state.loopback_only && !is_loopback_host(host) {
        return Err(ApiError::Forbidden(format!(
            "Host {host:?} is not a loopback name: a server bound to a loopback address \
             answers only http://localhost, 127.0.0.1 or [::1] (start it with --bind to \
             serve other names)"
        )));
    }
    if let Some(origin) = headers.get(header::ORIGIN) {
        let origin = origin.to_str().unwrap_or("");
        if !origin.eq_ignore_ascii_case(&format!("http://{host}")) {
            return Err(ApiError::Forbidden(format!(
                "cross-origin request from {origin:?} refused: only pages served by \
                 http://{host} may use this session"
            )));
        }
    }
    let path = request.uri().path();
    if request.method() == Method::POST {
        let kind = headers
            .get(header::CONTENT_TYPE)
            .and_then(|v| v.to_str().ok())
            .map(|v| {
                v.split(';')
                    .next()
                    .unwrap_or("")
                    .trim()
                    .to_ascii_lowercase()
            });
        let json = matches!(
            kind.as_deref(),
            Some("application/json" | "application/json-patch+json")
        );
        // A save may also come with no body at all (nothing a form sends).
        let bodiless_save = path == "/save" && kind.is_none() && body_is_empty(headers);
        if !(json || bodiless_save) {
            return Err(ApiError::UnsupportedType(format!(
                "{} needs Content-Type application/json-patch+json or application/json, \
                 got {}",
                path,
                kind.map_or("none".to_string(), |k| format!("{k:?}"))
            )));
        }
    }
    let shell = path == "/" || path.starts_with("/static/");
    if !shell {
        let from_query = (request.method() == Method::GET)
            .then(|| query_token(request.uri()))
            .flatten();
        state.authorize(headers, from_query.as_deref())?;
    }
    Ok(())
}

/// Whether a request declares no body.
fn body_is_empty(headers: &HeaderMap) -> bool {
    let length = headers
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok());
    headers.get(header::TRANSFER_ENCODING).is_none() && matches!(length, None | Some("0"))
}

/// The `token` query parameter, decoded.
fn query_token(uri: &Uri) -> Option<String> {
    let Query(pairs) = Query::<Vec<(String, String)>>::try_from_uri(uri).ok()?;
    pairs
        .into_iter()
        .find(|(k, _)| k == "token")
        .map(|(_, v)| v)
}

/// Whether `host` (a Host header, with or without a port) names this machine's
/// loopback interface.
pub fn is_loopback_host(host: &str) -> bool {
    let name = if let Some(rest) = host.strip_prefix('[') {
        match rest.split_once(']') {
            Some((inner, port))
                if port.is_empty() || port.strip_prefix(':').is_some_and(valid_port) =>
            {
                inner
            }
            _ => return false,
        }
    } else {
        match host.rsplit_once(':') {
            Some((name, port)) if valid_port(port) => name,
            Some(_) => return false,
            None => host,
        }
    };
    let name = name.to_ascii_lowercase();
    match name.parse::<std::net::IpAddr>() {
        Ok(ip) => ip.is_loopback(),
        Err(_) => name == "localhost" || name.ends_with(".localhost"),
    }
}

fn valid_port(port: &str) -> bool {
    !port.is_empty() && port.parse::<u16>().is_ok()
}

/// The security headers of every answer.
fn add_security_headers(headers: &mut HeaderMap, host: Option<&str>) {
    // Sockets to the served host only; `'self'` covers ws: in current browsers,
    // the explicit source covers older ones.
    let socket = host
        .filter(|h| {
            h.chars()
                .all(|c| c.is_ascii_alphanumeric() || ".-:[]".contains(c))
        })
        .map(|h| format!(" ws://{h}"))
        .unwrap_or_default();
    // 'wasm-unsafe-eval' lets the page compile WebAssembly (three.js's
    // MeshoptDecoder for `EXT_meshopt_compression`), not evaluate script text.
    let policy = format!(
        "default-src 'none'; script-src 'self' 'wasm-unsafe-eval'; style-src 'self'; img-src 'self' data: blob:; \
         connect-src 'self'{socket}; frame-ancestors 'none'; base-uri 'none'; form-action 'none'"
    );
    if let Ok(value) = HeaderValue::from_str(&policy) {
        headers.insert(header::CONTENT_SECURITY_POLICY, value);
    }
    headers.insert(header::X_FRAME_OPTIONS, HeaderValue::from_static("DENY"));
    headers.insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    headers.insert(
        header::REFERRER_POLICY,
        HeaderValue::from_static("no-referrer"),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loopback_names() {
        for host in [
            "localhost",
            "localhost:8080",
            "127.0.0.1:1",
            "127.1.2.3",
            "[::1]:8080",
            "[::1]",
            "app.localhost:80",
            "LOCALHOST",
        ] {
            assert!(is_loopback_host(host), "{host}");
        }
        for host in [
            "evil.example",
            "evil.example:8080",
            "localhost.evil.example",
            "10.0.0.1:8080",
            "[::2]:80",
            "localhost:99999",
            "localhost:",
            "",
        ] {
            assert!(!is_loopback_host(host), "{host}");
        }
    }

    #[test]
    fn the_token_may_come_in_the_query() {
        let token = |uri: &str| query_token(&uri.parse().unwrap());
        assert_eq!(token("/ws?vessel=V-1&token=a%20b"), Some("a b".into()));
        assert_eq!(token("/ws?vessel=V-1"), None);
        assert_eq!(token("/ws"), None);
    }
}
