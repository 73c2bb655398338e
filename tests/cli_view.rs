//! `shapegen view` and `shapegen report` end to end: the server serves the folder's files
//! and the embedded page, refuses paths out of the folder and methods other than GET,
//! survives files that come and go; the report embeds everything and fetches nothing.

mod support;

use std::fs;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::Path;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use support::view::serve;
use support::{fails, ok, s, skyline_scene};

/// A short run of the small skyline scene into `dir/run`.
fn short_run(dir: &Path) -> std::path::PathBuf {
    let scene = skyline_scene(dir);
    let out = dir.join("run");
    ok(&["run", s(&scene), "--cpu", "--out", s(&out)]);
    out
}

/// A response: status, headers (names lowercased) and body.
struct Reply {
    status: u16,
    headers: Vec<(String, String)>,
    body: Vec<u8>,
}

impl Reply {
    fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }
}

/// Sends one HTTP/1.1 request as written (`target` sent byte for byte, so that
/// `..` reaches the server unnormalized) and reads the whole response.
fn request(addr: SocketAddr, method: &str, target: &str, headers: &[(&str, &str)]) -> Reply {
    let mut stream = TcpStream::connect(addr).unwrap();
    let host = format!("127.0.0.1:{}", addr.port());
    let mut head = format!("{method} {target} HTTP/1.1\r\nConnection: close\r\n");
    if !headers.iter().any(|(n, _)| *n == "Host") {
        head += &format!("Host: {host}\r\n");
    }
    for (n, v) in headers {
        head += &format!("{n}: {v}\r\n");
    }
    head += "Content-Length: 0\r\n\r\n";
    stream.write_all(head.as_bytes()).unwrap();
    let mut raw = Vec::new();
    stream.read_to_end(&mut raw).unwrap();
    let split = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a complete response head");
    let head = String::from_utf8_lossy(&raw[..split]).into_owned();
    let mut lines = head.lines();
    let status = lines.next().unwrap().split_whitespace().nth(1).unwrap();
    let headers = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(n, v)| (n.trim().to_ascii_lowercase(), v.trim().to_owned()))
        .collect();
    Reply {
        status: status.parse().unwrap(),
        headers,
        body: raw[split + 4..].to_vec(),
    }
}

fn get(addr: SocketAddr, target: &str) -> Reply {
    request(addr, "GET", target, &[])
}

#[test]
fn a_run_writes_what_the_page_shows() {
    let dir = tempfile::tempdir().unwrap();
    let run = short_run(dir.path());
    let live: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(run.join("run.json")).unwrap()).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(run.join("summary.json")).unwrap()).unwrap();
    for key in ["method", "seed", "evaluations", "best_fitness", "elapsed_s"] {
        assert_eq!(live[key], summary[key], "{key}");
    }
    assert_eq!(live["generation"], summary["generations"]);
    assert_eq!(live["running"], false);
    let camera: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(run.join("camera.json")).unwrap()).unwrap();
    assert_eq!(camera["width"], 160);
    assert_eq!(camera["view_projection"].as_array().unwrap().len(), 16);
    let target = image::open(run.join("target.png")).unwrap();
    assert_eq!((target.width(), target.height()), (160, 90));
}

#[test]
fn the_server_serves_the_folder_and_refuses_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let run = short_run(dir.path());
    fs::write(dir.path().join("secret.txt"), "TOP-SECRET-CONTENT").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(dir.path().join("secret.txt"), run.join("leak.txt")).unwrap();
    let served = serve(&["view", s(&run)]);
    let addr = served.addr;
    assert!(addr.ip().is_loopback(), "{addr}");

    let page = get(addr, "/");
    assert_eq!(page.status, 200);
    assert!(String::from_utf8_lossy(&page.body).contains("/assets/viewer.js"));
    let js = get(addr, "/assets/vendor/three/three.core.js");
    assert_eq!(js.status, 200);
    assert!(js.header("content-encoding").is_none());
    assert!(String::from_utf8_lossy(&js.body).contains("REVISION"));
    let gz = request(
        addr,
        "GET",
        "/assets/vendor/three/three.core.js",
        &[("Accept-Encoding", "gzip, deflate")],
    );
    assert_eq!(gz.header("content-encoding"), Some("gzip"));
    assert!(gz.body.len() < js.body.len() / 2);

    let summary = get(addr, "/files/summary.json");
    assert_eq!(summary.status, 200);
    assert_eq!(summary.body, fs::read(run.join("summary.json")).unwrap());
    let glb = get(addr, "/files/best.glb?t=1");
    assert_eq!(glb.status, 200);
    assert_eq!(glb.body, fs::read(run.join("best.glb")).unwrap());
    assert_eq!(glb.header("content-type"), Some("model/gltf-binary"));
    let tag = glb.header("etag").expect("an entity tag").to_owned();
    let again = request(addr, "GET", "/files/best.glb", &[("If-None-Match", &tag)]);
    assert_eq!(again.status, 304);
    assert!(again.body.is_empty());

    let list: serde_json::Value = serde_json::from_slice(&get(addr, "/list").body).unwrap();
    let files: Vec<&str> = list["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    for f in [
        "best.glb",
        "fitness.csv",
        "run.json",
        "summary.json",
        "target.png",
    ] {
        assert!(files.contains(&f), "{f} not in {files:?}");
    }
    assert!(!files.contains(&"leak.txt"));

    // A parent step, spelt apart from the `/` after it.
    let up = "..";
    for bad in [
        format!("/files/{up}/secret.txt"),
        "/files/%2e%2e/secret.txt".into(),
        "/files/..%2fsecret.txt".into(),
        "/files//etc/passwd".into(),
        "/files/a%5c..%5c..%5csecret.txt".into(),
        format!("/assets/{up}/{up}/Cargo.toml"),
    ] {
        let bad = bad.as_str();
        let reply = get(addr, bad);
        assert_eq!(reply.status, 400, "{bad}");
        assert!(!String::from_utf8_lossy(&reply.body).contains("TOP-SECRET"));
    }
    #[cfg(unix)]
    assert_eq!(get(addr, "/files/leak.txt").status, 403);
    assert_eq!(get(addr, "/files/missing.glb").status, 404);
    assert_eq!(get(addr, "/etc/passwd").status, 404);
    assert_eq!(get(addr, "/assets/missing.js").status, 404);
    for method in ["POST", "PUT", "DELETE", "HEAD", "OPTIONS"] {
        let reply = request(addr, method, "/files/summary.json", &[]);
        assert_eq!(reply.status, 405, "{method}");
        assert_eq!(reply.header("allow"), Some("GET"));
    }
    // Another site's page reaching 127.0.0.1 through its own name (DNS rebinding).
    let rebound = request(
        addr,
        "GET",
        "/files/summary.json",
        &[("Host", "evil.example:80")],
    );
    assert_eq!(rebound.status, 403);

    // Files that go and come back, as a run replaces them, never stop the server.
    fs::remove_file(run.join("best.glb")).unwrap();
    assert_eq!(get(addr, "/files/best.glb").status, 404);
    fs::write(run.join("best.glb"), b"not yet a model").unwrap();
    assert_eq!(get(addr, "/files/best.glb").body, b"not yet a model");
    fs::remove_dir_all(&run).unwrap();
    assert_eq!(get(addr, "/files/summary.json").status, 404);
    assert_eq!(get(addr, "/list").status, 200);
    assert_eq!(get(addr, "/").status, 200);
}

#[test]
fn view_and_run_refuse_mistakes() {
    let dir = tempfile::tempdir().unwrap();
    let err = fails(&["view", s(&dir.path().join("missing"))]);
    assert!(err.contains("is not a folder"), "{err}");
    let scene = skyline_scene(dir.path());
    let err = fails(&[
        "run",
        s(&scene),
        "--port",
        "8080",
        "--out",
        s(&dir.path().join("x")),
    ]);
    assert!(err.contains("give --view too"), "{err}");
}

#[test]
fn run_view_serves_the_run_folder() {
    let dir = tempfile::tempdir().unwrap();
    let scene = skyline_scene(dir.path());
    let out = dir.path().join("run");
    let served = serve(&["run", s(&scene), "--cpu", "--view", "--out", s(&out)]);
    support::wait_for(&out.join("summary.json"));
    let reply = get(served.addr, "/files/summary.json");
    assert_eq!(reply.status, 200);
    assert_eq!(reply.body, fs::read(out.join("summary.json")).unwrap());
}

#[test]
fn the_report_is_self_contained() {
    let dir = tempfile::tempdir().unwrap();
    let run = short_run(dir.path());
    let printed = ok(&["report", s(&run)]);
    assert!(printed.contains("report.html"), "{printed}");
    let html = fs::read_to_string(run.join("report.html")).unwrap();

    // Nothing is loaded from anywhere: no attribute names a URL, and every module of
    // the import map is a data: URL.
    for attribute in ["src=\"", "href=\""] {
        assert!(!html.contains(attribute), "the report loads `{attribute}…`");
    }
    let open = "<script type=\"importmap\">";
    let map_start = html.find(open).expect("an import map") + open.len();
    let map_end = map_start + html[map_start..].find("</script>").unwrap();
    let map: serde_json::Value = serde_json::from_str(&html[map_start..map_end]).unwrap();
    let imports = map["imports"].as_object().unwrap();
    assert!(imports.contains_key("three"));
    for (key, url) in imports {
        assert!(
            url.as_str()
                .unwrap()
                .starts_with("data:text/javascript;base64,"),
            "{key}"
        );
    }
    // The model, the curve and the numbers are inline, byte for byte.
    let open = "window.SHAPEGEN_FILES = ";
    let start = html.find(open).expect("the files") + open.len();
    let end = start + html[start..].find(";</script>").unwrap();
    let files: serde_json::Value = serde_json::from_str(&html[start..end]).unwrap();
    for name in [
        "best.glb",
        "fitness.csv",
        "summary.json",
        "target.png",
        "camera.json",
    ] {
        let inline = STANDARD
            .decode(
                files[name]
                    .as_str()
                    .unwrap_or_else(|| panic!("{name} inline")),
            )
            .unwrap();
        assert_eq!(inline, fs::read(run.join(name)).unwrap(), "{name}");
    }
    assert!(files.get("checkpoint.json").is_none());

    let err = fails(&["report", s(dir.path())]);
    assert!(err.contains("fitness.csv"), "{err}");
}
