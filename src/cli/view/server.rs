//! The viewer's HTTP server: the page and its assets from the binary, and the run
//! folder's files, read-only, to GET requests only.

use std::io::Read;
use std::net::{IpAddr, SocketAddr};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant, UNIX_EPOCH};

use anyhow::Context;
use percent_encoding::percent_decode_str;
use tiny_http::{Header, Method, Request, Response, Server};

use super::assets::asset;
use super::listing::listing;
use super::path::{Refusal, RequestPath};

/// Largest file the server sends, in bytes: larger ones are refused, not read.
const MAX_FILE: u64 = 512 << 20;
/// Longest a request with `?wait=TAG` is held while the file still has that tag.
const MAX_WAIT: Duration = Duration::from_secs(10);
/// Most requests answered at once; more are answered `503` at once.
const MAX_REQUESTS: usize = 32;

/// A bound viewer server for one folder.
pub struct Viewer {
    server: Server,
    root: PathBuf,
    addr: SocketAddr,
}

impl Viewer {
    /// Binds a server for `root` at `addr` (port 0: any free port).
    ///
    /// # Errors
    /// When `root` is not a folder or the address cannot be bound.
    pub fn bind(root: &Path, addr: SocketAddr) -> anyhow::Result<Viewer> {
        anyhow::ensure!(
            root.is_dir(),
            "`{}` is not a folder: give a run's --out folder",
            root.display()
        );
        let server =
            Server::http(addr).map_err(|e| anyhow::anyhow!("cannot listen on {addr}: {e}"))?;
        let addr = server
            .server_addr()
            .to_ip()
            .context("the server has no IP address")?;
        Ok(Viewer {
            server,
            root: root.to_owned(),
            addr,
        })
    }

    /// The address the server listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's URL.
    pub fn url(&self) -> String {
        let host = match self.addr.ip() {
            ip if ip.is_unspecified() => "127.0.0.1".to_owned(),
            IpAddr::V6(ip) => format!("[{ip}]"),
            IpAddr::V4(ip) => ip.to_string(),
        };
        format!("http://{host}:{}/", self.addr.port())
    }

    /// Answers requests until the process ends, each on a thread of its own (a
    /// request may wait for a file to change), at most 32 at once.
    pub fn serve(&self) {
        let busy = Arc::new(AtomicUsize::new(0));
        for request in self.server.incoming_requests() {
            if busy.fetch_add(1, Ordering::SeqCst) >= MAX_REQUESTS {
                busy.fetch_sub(1, Ordering::SeqCst);
                let _ = request.respond(text(503, "too many requests at once"));
                continue;
            }
            let (root, addr, busy) = (self.root.clone(), self.addr, Arc::clone(&busy));
            std::thread::spawn(move || {
                let answer = answer(&root, addr, &request);
                // A client that went away is no error of the server's.
                let _ = request.respond(answer);
                busy.fetch_sub(1, Ordering::SeqCst);
            });
        }
    }

    /// Answers requests on a thread of its own (as `shapegen run --view` does beside
    /// its search); a page open costs a few small file reads per save of the run.
    pub fn spawn(self) -> JoinHandle<()> {
        std::thread::Builder::new()
            .name("shapegen-view".into())
            .spawn(move || self.serve())
            .expect("the viewer's thread starts")
    }
}

/// A response with any reader as its body.
type Answer = Response<Box<dyn Read + Send>>;

fn respond(status: u16, mime: &str, body: Vec<u8>) -> Answer {
    let len = body.len();
    Response::new(
        status.into(),
        vec![header("Content-Type", mime)],
        Box::new(std::io::Cursor::new(body)) as Box<dyn Read + Send>,
        Some(len),
        None,
    )
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("a valid header")
}

fn text(status: u16, message: &str) -> Answer {
    respond(
        status,
        "text/plain; charset=utf-8",
        format!("{message}\n").into_bytes(),
    )
}

fn request_header<'r>(request: &'r Request, name: &'static str) -> Option<&'r str> {
    request
        .headers()
        .iter()
        .find(|h| h.field.equiv(name))
        .map(|h| h.value.as_str())
}

/// Whether the request's `Host` names the server as a browser on this machine would:
/// a page of another site that resolves its name to 127.0.0.1 (DNS rebinding) sends
/// its own name and is refused. Any host is accepted when the server listens beyond
/// the loopback interface.
fn host_allowed(request: &Request, addr: SocketAddr) -> bool {
    if !addr.ip().is_loopback() {
        return true;
    }
    let Some(host) = request_header(request, "Host") else {
        return false;
    };
    let port = addr.port();
    ["127.0.0.1", "localhost", "[::1]"]
        .iter()
        .any(|name| host.eq_ignore_ascii_case(&format!("{name}:{port}")))
}

/// The answer to one request.
fn answer(root: &Path, addr: SocketAddr, request: &Request) -> Answer {
    if *request.method() != Method::Get {
        return text(405, "only GET is served: the viewer is read-only")
            .with_header(header("Allow", "GET"));
    }
    if !host_allowed(request, addr) {
        return text(403, "refused: the Host header does not name this server");
    }
    let answer = match RequestPath::parse(request.url()) {
        Ok(RequestPath::Page) => serve_asset(request, "index.html"),
        Ok(RequestPath::Asset(name)) => serve_asset(request, &name),
        Ok(RequestPath::List) => match serde_json::to_vec(&listing(root)) {
            Ok(json) => respond(200, "application/json", json),
            Err(e) => text(500, &format!("cannot list the folder: {e}")),
        },
        Ok(path @ RequestPath::File(_)) => match path.file_in(root) {
            Ok(file) => serve_file(request, &file),
            Err(refusal) => text(refusal.status(), &refusal.to_string()),
        },
        Err(refusal) => text(refusal.status(), &refusal.to_string()),
    };
    answer
        .with_header(header("Cache-Control", "no-cache"))
        .with_header(header("X-Content-Type-Options", "nosniff"))
        .with_header(header("Referrer-Policy", "no-referrer"))
}

/// An embedded asset, gzipped as stored when the client takes gzip.
fn serve_asset(request: &Request, name: &str) -> Answer {
    let Some(asset) = asset(name) else {
        return text(404, &Refusal::NotFound.to_string());
    };
    if !asset.gzipped {
        return respond(200, asset.mime, asset.bytes.to_vec());
    }
    let takes_gzip = request_header(request, "Accept-Encoding")
        .is_some_and(|v| v.split(',').any(|e| e.trim().starts_with("gzip")));
    if takes_gzip {
        return respond(200, asset.mime, asset.bytes.to_vec())
            .with_header(header("Content-Encoding", "gzip"));
    }
    match asset.unpacked() {
        Ok(body) => respond(200, asset.mime, body),
        Err(e) => text(500, &format!("embedded asset {name} does not unpack: {e}")),
    }
}

/// The entity tag of the file at `path` (its size and modification time), `None` if
/// it is gone.
fn entity_tag(path: &Path) -> Option<(String, u64)> {
    let meta = std::fs::metadata(path).ok()?;
    let modified = meta
        .modified()
        .ok()
        .and_then(|t| t.duration_since(UNIX_EPOCH).ok())
        .map_or(0, |d| d.as_nanos());
    Some((format!("\"{:x}-{modified:x}\"", meta.len()), meta.len()))
}

/// The `wait` parameter of the request's query, if any.
fn wait_for_change(request: &Request) -> Option<String> {
    let query = request.url().split_once('?')?.1;
    let value = query.split('&').find_map(|kv| kv.strip_prefix("wait="))?;
    Some(percent_decode_str(value).decode_utf8_lossy().into_owned())
}

/// A file of the folder, with an entity tag from its size and modification time so
/// that a page polling it gets `304 Not Modified` until the run replaces it. With
/// `?wait=TAG`, the answer waits (up to [`MAX_WAIT`]) until the file's tag is another:
/// a page follows a run with one request per change.
fn serve_file(request: &Request, path: &Path) -> Answer {
    if let Some(tag) = wait_for_change(request) {
        let start = Instant::now();
        while entity_tag(path).is_some_and(|(t, _)| t == tag) && start.elapsed() < MAX_WAIT {
            std::thread::sleep(Duration::from_millis(50));
        }
    }
    let Some((etag, len)) = entity_tag(path) else {
        return text(404, &Refusal::NotFound.to_string());
    };
    if len > MAX_FILE {
        return text(413, &format!("file larger than {} MiB", MAX_FILE >> 20));
    }
    if request_header(request, "If-None-Match") == Some(etag.as_str()) {
        return respond(304, mime_of(path), Vec::new()).with_header(header("ETag", &etag));
    }
    // A file replaced between the two calls (the run renames a new one over it) reads
    // whole, old or new: the run never writes in place.
    match std::fs::read(path) {
        Ok(bytes) => respond(200, mime_of(path), bytes).with_header(header("ETag", &etag)),
        Err(_) => text(404, &Refusal::NotFound.to_string()),
    }
}

/// The MIME type of a file of the folder, by its extension.
fn mime_of(path: &Path) -> &'static str {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or_default()
    {
        "json" => "application/json",
        "csv" => "text/csv; charset=utf-8",
        "md" | "txt" | "obj" | "mtl" | "toml" => "text/plain; charset=utf-8",
        "png" => "image/png",
        "svg" => "image/svg+xml",
        "glb" => "model/gltf-binary",
        "html" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}
