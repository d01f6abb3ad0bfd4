//! Other web pages cannot drive a session: a cross-origin edit or save, a
//! "simple" request a form could send (`text/plain`), a page reached through
//! another host name (DNS rebinding) and a cross-origin WebSocket are refused by
//! a default `vesselcad serve` (no token), and the design file is left as it was;
//! every answer carries the security headers.

mod server_support;

use serde_json::json;
use server_support::{ServerProcess, design_copy};

/// A request (method, path, headers, body) and the status it must get.
type Case<'a> = (&'a str, &'a str, Vec<(&'a str, &'a str)>, Vec<u8>, u16);

fn patch() -> Vec<u8> {
    json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": 10 }])
        .to_string()
        .into_bytes()
}

#[test]
fn cross_origin_and_simple_requests_cannot_edit_or_save() {
    let design = design_copy("storage-tank.json", "security-origin");
    let file = std::fs::read(&*design).unwrap();
    let server = ServerProcess::start(&design, &[]);
    let own = server.url();
    let evil = [("Origin", "http://evil.example")];
    let cases: Vec<Case> = vec![
        // What the report found: a cross-origin text/plain POST was accepted.
        (
            "POST",
            "/edit",
            vec![
                ("Origin", "http://evil.example"),
                ("Content-Type", "text/plain"),
            ],
            patch(),
            403,
        ),
        ("POST", "/edit", evil.to_vec(), patch(), 403),
        ("POST", "/save", evil.to_vec(), vec![], 403),
        ("POST", "/edit", vec![("Origin", "null")], patch(), 403),
        // Same origin, but a type an HTML form can send.
        (
            "POST",
            "/edit",
            vec![("Content-Type", "text/plain")],
            patch(),
            415,
        ),
        (
            "POST",
            "/edit",
            vec![("Content-Type", "application/x-www-form-urlencoded")],
            patch(),
            415,
        ),
        (
            "POST",
            "/save",
            vec![("Content-Type", "text/plain")],
            b"x".to_vec(),
            415,
        ),
        // Reading from another origin, and its WebSocket.
        ("GET", "/design.json", evil.to_vec(), vec![], 403),
        (
            "GET",
            "/ws",
            vec![
                ("Origin", "http://evil.example"),
                ("Upgrade", "websocket"),
                ("Connection", "Upgrade"),
                ("Sec-WebSocket-Version", "13"),
                ("Sec-WebSocket-Key", "dGhlIHNhbXBsZSBub25jZQ=="),
            ],
            vec![],
            403,
        ),
    ];
    for (method, path, headers, body, status) in &cases {
        let r = server.request(method, path, headers, body);
        assert_eq!(
            r.status,
            *status,
            "{method} {path} {headers:?}: {}",
            r.text()
        );
        let kind = r.json()["kind"].as_str().unwrap().to_string();
        assert!(
            ["forbidden", "unsupported_type"].contains(&kind.as_str()),
            "{kind}"
        );
    }
    assert_eq!(
        std::fs::read(&*design).unwrap(),
        file,
        "the file was written"
    );
    let r = server.request("GET", "/design.json", &[], b"");
    assert_eq!(r.header("x-vesselcad-revision"), Some("0"));

    // The page's own requests pass.
    let r = server.request("POST", "/edit", &[("Origin", own.as_str())], &patch());
    assert_eq!(r.status, 200, "{}", r.text());
    let r = server.request("POST", "/save", &[("Origin", own.as_str())], b"");
    assert_eq!(r.status, 200, "{}", r.text());
}

#[test]
fn only_loopback_host_names_are_answered() {
    let design = design_copy("storage-tank.json", "security-host");
    let server = ServerProcess::start(&design, &[]);
    let port = server.address.port();
    for host in [
        "evil.example".to_string(),
        format!("evil.example:{port}"),
        format!("localhost.evil.example:{port}"),
        format!("192.168.1.20:{port}"),
    ] {
        let r = server.request("GET", "/design.json", &[("Host", host.as_str())], b"");
        assert_eq!(r.status, 403, "Host {host}: {}", r.text());
        assert!(r.text().contains("not a loopback name"), "{}", r.text());
        let r = server.request("GET", "/", &[("Host", host.as_str())], b"");
        assert_eq!(r.status, 403, "page with Host {host}");
    }
    for host in [format!("localhost:{port}"), format!("127.0.0.1:{port}")] {
        let r = server.request("GET", "/design.json", &[("Host", host.as_str())], b"");
        assert_eq!(r.status, 200, "Host {host}: {}", r.text());
    }
}

#[test]
fn every_answer_carries_the_security_headers() {
    let design = design_copy("storage-tank.json", "security-headers");
    let server = ServerProcess::start(&design, &[]);
    for path in ["/", "/static/viewer.js", "/design.json", "/nowhere"] {
        let r = server.request("GET", path, &[], b"");
        let policy = r.header("content-security-policy").unwrap_or_default();
        assert!(
            policy.contains("frame-ancestors 'none'") && policy.contains("script-src 'self'"),
            "{path}: {policy:?}"
        );
        assert_eq!(r.header("x-frame-options"), Some("DENY"), "{path}");
        assert_eq!(
            r.header("x-content-type-options"),
            Some("nosniff"),
            "{path}"
        );
    }
    // The page needs no inline script the policy would block.
    let page = server.request("GET", "/", &[], b"").text();
    assert!(
        !page.contains("<script>") && !page.contains("importmap"),
        "{page}"
    );
}

#[test]
fn idle_connections_are_closed_and_cannot_starve_the_server() {
    use std::io::{Read, Write};
    let design = design_copy("storage-tank.json", "security-idle");
    let server = ServerProcess::start(&design, &["--max-connections", "8", "--idle-timeout", "1"]);
    // More idle sockets than the server serves at once; some stop mid-headers.
    let mut idle: Vec<std::net::TcpStream> = (0..24)
        .map(|_| std::net::TcpStream::connect(server.address).unwrap())
        .collect();
    for s in idle.iter_mut().take(8) {
        s.write_all(b"GET /design.json HTTP/1.1\r\nHost: 127.0.0.1\r\n")
            .unwrap();
    }
    // A real request is still answered: idle ones are closed to make room.
    let r = server.request("GET", "/design.json", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    // Every idle socket was closed by the server (end of stream or reset), none
    // left open until the client's own timeout.
    for mut s in idle {
        s.set_read_timeout(Some(server_support::TIMEOUT)).unwrap();
        let mut rest = Vec::new();
        match s.read_to_end(&mut rest) {
            Ok(_) => {}
            Err(e) => assert!(
                !matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                ),
                "an idle socket stayed open: {e}"
            ),
        }
    }
}

/// The idle timeout cuts sockets that move no byte, not slow ones: a request
/// whose body is trickled in for well over the timeout (a byte group every
/// tenth of it) is answered, while a socket opened beside it and left silent
/// is closed.
#[test]
fn a_slow_but_active_request_is_not_cut_while_an_idle_one_is() {
    use std::io::{Read, Write};
    use std::time::{Duration, Instant};
    let design = design_copy("storage-tank.json", "security-slow");
    let server = ServerProcess::start(&design, &["--idle-timeout", "2"]);
    let mut idle = std::net::TcpStream::connect(server.address).unwrap();
    let mut slow = std::net::TcpStream::connect(server.address).unwrap();
    let body = patch();
    let head = format!(
        "POST /edit HTTP/1.1\r\nHost: {}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n",
        server.address,
        body.len()
    );
    slow.write_all(head.as_bytes()).unwrap();
    let start = Instant::now();
    for chunk in body.chunks(body.len().div_ceil(25)) {
        std::thread::sleep(Duration::from_millis(200));
        slow.write_all(chunk).unwrap();
    }
    let trickled = start.elapsed();
    assert!(trickled > Duration::from_secs(4), "{trickled:?}");
    slow.set_read_timeout(Some(server_support::TIMEOUT))
        .unwrap();
    let mut answer = String::new();
    slow.read_to_string(&mut answer).unwrap();
    assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    // The silent socket, older than the timeout by now, was closed by the
    // server: end of stream (or a reset), not the client's own timeout.
    idle.set_read_timeout(Some(server_support::TIMEOUT))
        .unwrap();
    let mut rest = Vec::new();
    let waited = Instant::now();
    match idle.read_to_end(&mut rest) {
        Ok(_) => assert!(rest.is_empty(), "{}", String::from_utf8_lossy(&rest)),
        Err(e) => assert!(
            !matches!(
                e.kind(),
                std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
            ),
            "the idle socket stayed open: {e}"
        ),
    }
    assert!(waited.elapsed() < server_support::TIMEOUT);
}
