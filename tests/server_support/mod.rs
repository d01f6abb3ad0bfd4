//! Shared helpers of the live-session tests: a `vesselcad serve` child process on
//! a free loopback port (killed on drop), a copy of an example design in a fresh
//! folder, and a minimal HTTP/1.1 client over `TcpStream` (raw, so tests can send
//! exactly the bytes they mean, including paths a client library would clean up).

#![expect(dead_code, reason = "each test binary uses a different subset")]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

/// How long any single request or start-up may take before the test fails.
pub const TIMEOUT: Duration = Duration::from_secs(60);

/// A copy of an example design in a fresh folder of its own, removed (with
/// whatever the test wrote there: journals, saved designs) when dropped. Derefs
/// to the design's path.
pub struct DesignCopy {
    path: PathBuf,
    _dir: tempfile::TempDir,
}

impl std::ops::Deref for DesignCopy {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for DesignCopy {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

/// A fresh folder holding a copy of `examples/designs/<example>`; returns the
/// design path inside it (the folder goes when the copy is dropped).
pub fn design_copy(example: &str, test: &str) -> DesignCopy {
    let dir = tempfile::Builder::new()
        .prefix(&format!("vesselcad-{test}-"))
        .tempdir()
        .unwrap();
    let path = dir.path().join("design.json");
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/designs")
        .join(example);
    std::fs::copy(source, &path).unwrap();
    DesignCopy { path, _dir: dir }
}

/// A running `vesselcad serve`, killed (SIGKILL) when dropped.
pub struct ServerProcess {
    pub child: Child,
    pub address: SocketAddr,
}

impl ServerProcess {
    /// Starts the real binary on a free loopback port and waits for its URL.
    pub fn start(design: &Path, extra: &[&str]) -> ServerProcess {
        // 2 mm unless the test asks for another tolerance.
        let tolerance: &[&str] = if extra.contains(&"--tolerance") {
            &[]
        } else {
            &["--tolerance", "2"]
        };
        let mut child = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
            .arg("serve")
            .arg(design)
            .args(["--port", "0", "--bind", "127.0.0.1"])
            .args(tolerance)
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("cannot start vesselcad serve");
        let stdout = child.stdout.take().unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut lines = BufReader::new(stdout).lines();
            if let Some(Ok(line)) = lines.next() {
                let _ = tx.send(line);
            }
            // Keep draining so the server never blocks on a full pipe.
            for _ in lines {}
        });
        let line = match rx.recv_timeout(TIMEOUT) {
            Ok(line) => line,
            Err(_) => {
                let _ = child.kill();
                panic!("vesselcad serve printed no URL within {TIMEOUT:?}");
            }
        };
        let address = line
            .trim()
            .strip_prefix("vesselcad serve: http://")
            .and_then(|s| s.strip_suffix('/'))
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("unexpected first line: {line}"));
        ServerProcess { child, address }
    }

    /// `http://address`.
    pub fn url(&self) -> String {
        format!("http://{}", self.address)
    }

    /// SIGKILL and wait.
    pub fn kill9(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// SIGTERM (clean shutdown) and wait, bounded; returns the exit success.
    pub fn terminate(&mut self) -> bool {
        let pid = self.child.id().to_string();
        let _ = Command::new("kill").args(["-TERM", &pid]).status();
        let start = Instant::now();
        while start.elapsed() < TIMEOUT {
            if let Ok(Some(status)) = self.child.try_wait() {
                return status.success();
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        self.kill9();
        false
    }

    /// A request; see [`request`].
    pub fn request(
        &self,
        method: &str,
        path: &str,
        headers: &[(&str, &str)],
        body: &[u8],
    ) -> Response {
        request(self.address, method, path, headers, body)
    }

    /// GET, body as JSON.
    pub fn get_json(&self, path: &str) -> Value {
        let r = self.request("GET", path, &[], b"");
        assert_eq!(r.status, 200, "GET {path}: {}", r.text());
        r.json()
    }

    /// POST a JSON Patch to /edit.
    pub fn edit(&self, patch: &Value) -> Response {
        self.request("POST", "/edit", &[], patch.to_string().as_bytes())
    }
}

impl Drop for ServerProcess {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// An HTTP response.
#[derive(Debug)]
pub struct Response {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

impl Response {
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.text()))
    }
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }
}

/// One HTTP/1.1 request with `Connection: close`; the path is sent as given.
pub fn request(
    address: SocketAddr,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
) -> Response {
    let mut stream = TcpStream::connect_timeout(&address, TIMEOUT).unwrap();
    stream.set_read_timeout(Some(TIMEOUT)).unwrap();
    stream.set_write_timeout(Some(TIMEOUT)).unwrap();
    let given = |name: &str| headers.iter().any(|(n, _)| n.eq_ignore_ascii_case(name));
    let mut head = format!("{method} {path} HTTP/1.1\r\n");
    // Host and Content-Type unless the test gives its own.
    if !given("Host") {
        head.push_str(&format!("Host: {address}\r\n"));
    }
    head.push_str(&format!(
        "Connection: close\r\nContent-Length: {}\r\n",
        body.len()
    ));
    if !body.is_empty() && !given("Content-Type") {
        head.push_str("Content-Type: application/json-patch+json\r\n");
    }
    for (name, value) in headers {
        head.push_str(&format!("{name}: {value}\r\n"));
    }
    head.push_str("\r\n");
    stream.write_all(head.as_bytes()).unwrap();
    // The server may answer (413) before reading a large body: ignore a reset here.
    let _ = stream.write_all(body);
    let mut raw = Vec::new();
    let _ = stream.read_to_end(&mut raw);
    let split = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no HTTP head in {:?}", String::from_utf8_lossy(&raw)));
    let head = String::from_utf8_lossy(&raw[..split]).into_owned();
    let mut lines = head.split("\r\n");
    let status = lines
        .next()
        .and_then(|l| l.split(' ').nth(1))
        .and_then(|s| s.parse().ok())
        .unwrap();
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(n, v)| (n.trim().to_string(), v.trim().to_string()))
        .collect();
    let mut body = raw[split + 4..].to_vec();
    let chunked = headers
        .iter()
        .any(|(n, v)| n.eq_ignore_ascii_case("transfer-encoding") && v.contains("chunked"));
    if chunked {
        body = dechunk(&body);
    }
    Response {
        status,
        headers,
        body,
    }
}

/// Decodes a chunked body.
fn dechunk(mut data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let Some(end) = data.windows(2).position(|w| w == b"\r\n") else {
            return out;
        };
        let size_text = String::from_utf8_lossy(&data[..end]);
        let size = usize::from_str_radix(size_text.split(';').next().unwrap_or("0").trim(), 16)
            .unwrap_or(0);
        if size == 0 {
            return out;
        }
        let start = end + 2;
        out.extend_from_slice(&data[start..(start + size).min(data.len())]);
        data = &data[(start + size + 2).min(data.len())..];
    }
}
