//! The server through real HTTP on a loopback port: the page and its assets, an answer of
//! each endpoint, and the refusals — malformed JSON, wrong fields, unknown endpoints, wrong
//! methods, bodies over the limit — each a JSON error with a 4xx status, after which the
//! server still answers.

use serde_json::{Value, json};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::sync::OnceLock;
use std::time::Duration;

/// The studio on a free port, started once for every test of this binary.
pub(crate) fn server() -> SocketAddr {
    static ADDR: OnceLock<SocketAddr> = OnceLock::new();
    *ADDR.get_or_init(|| {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            spline_studio::run("127.0.0.1", 0, |addr| {
                let _ = tx.send(addr);
            })
        });
        rx.recv_timeout(Duration::from_secs(30))
            .expect("the studio binds a port")
    })
}

/// Sends one HTTP/1.1 request and returns the status, the content type and the body.
fn request(method: &str, path: &str, body: &[u8]) -> (u16, String, String) {
    let mut stream = TcpStream::connect(server()).expect("connect");
    stream
        .set_read_timeout(Some(Duration::from_secs(60)))
        .expect("timeout");
    let head = format!(
        "{method} {path} HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    );
    stream.write_all(head.as_bytes()).expect("write head");
    // The server may refuse a large body before reading it: a failed write is fine then.
    let _ = stream.write_all(body);
    let mut raw = Vec::new();
    let _ = stream.read_to_end(&mut raw);
    let text = String::from_utf8_lossy(&raw).into_owned();
    let (head, body) = text.split_once("\r\n\r\n").expect("an HTTP answer");
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .expect("a status");
    let content_type = head
        .lines()
        .find_map(|l| {
            l.to_ascii_lowercase()
                .strip_prefix("content-type: ")
                .map(str::to_owned)
        })
        .unwrap_or_default();
    (status, content_type, body.to_owned())
}

fn post(name: &str, body: &Value) -> (u16, Value) {
    let (status, content_type, text) =
        request("POST", &format!("/api/{name}"), body.to_string().as_bytes());
    assert!(
        content_type.starts_with("application/json"),
        "{content_type}"
    );
    (status, serde_json::from_str(&text).expect("a JSON answer"))
}

fn assert_json_error(status: u16, content_type: &str, body: &str, expected: u16, words: &str) {
    assert_eq!(status, expected, "{body}");
    assert!(
        content_type.starts_with("application/json"),
        "{content_type}"
    );
    let value: Value = serde_json::from_str(body).expect("a JSON error");
    let message = value["error"].as_str().expect("an error message");
    assert!(!message.contains('\n'), "one line: {message}");
    assert!(
        message.contains(words),
        "{message:?} should mention {words:?}"
    );
}

#[test]
fn the_page_and_its_assets_are_served_from_the_binary() {
    let (status, content_type, body) = request("GET", "/", b"");
    assert_eq!(status, 200);
    assert!(content_type.starts_with("text/html"));
    assert!(body.contains("<svg id=\"canvas\"") && body.contains("/studio.js"));
    // No network: nothing is fetched from another host.
    assert!(!body.contains("src=\"http") && !body.contains("href=\"http"));
    let (status, content_type, script) = request("GET", "/studio.js", b"");
    assert_eq!(status, 200);
    assert!(content_type.starts_with("text/javascript"));
    assert!(!script.contains("https://") && script.contains("/api/"));
    let (status, content_type, _) = request("GET", "/studio.css", b"");
    assert_eq!((status, content_type.starts_with("text/css")), (200, true));
}

#[test]
fn each_endpoint_answers() {
    let points = json!([[0, 0], [1, 2], [2, -1], [3, 1], [4, 0], [5, 1.5], [6, 0]]);
    let (status, a) = post(
        "bezier",
        &json!({"control_points": [[0, 0], [1, 2], [2, 0]], "t": 0.25, "elevate": 2}),
    );
    assert_eq!(status, 200, "{a}");
    // x(1/4) of the quadratic: (3/4)² P0 + 2 (3/4)(1/4) P1 + (1/4)² P2 = (0.5, 0.75).
    assert_eq!(a["point"], json!([0.5, 0.75]));
    // The de Casteljau triangle by hand: level 1 is (3/4) P_i + (1/4) P_{i+1}; the left half
    // of the subdivision is P0, the first point of each level; the right half the last ones.
    assert_eq!(a["casteljau"][1], json!([[0.25, 0.5], [1.25, 1.5]]));
    assert_eq!(a["left"], json!([[0.0, 0.0], [0.25, 0.5], [0.5, 0.75]]));
    assert_eq!(a["right"], json!([[0.5, 0.75], [1.25, 1.5], [2.0, 0.0]]));
    assert_eq!(a["elevated"].as_array().map(Vec::len), Some(5));
    let (status, a) = post(
        "bspline",
        &json!({"degree": 3, "control_points": points, "insert": 0.3}),
    );
    assert_eq!(status, 200, "{a}");
    assert_eq!(
        a["curve"]["control_points"].as_array().map(Vec::len),
        Some(8)
    );
    let (status, a) = post("interpolate", &json!({"points": points, "degree": 3}));
    assert_eq!(
        (status, a["fits"].as_array().map(Vec::len)),
        (200, Some(3)),
        "{a}"
    );
    let (status, a) = post(
        "approximate",
        &json!({"points": points, "degree": 2, "control_points": 4, "correct": 5}),
    );
    assert_eq!(status, 200, "{a}");
    assert_eq!(a["projections"].as_array().map(Vec::len), Some(7));
    let (status, f) = post("features", &json!({"curve": a["curve"]}));
    assert_eq!(status, 200, "{f}");
    assert!(f["comb"].as_array().is_some_and(|c| c.len() > 10));
    let (status, a) = post(
        "load",
        &json!({"text": "NACA 0012\n1.0 0.0013\n0.5 0.0529\n0.0 0.0\n0.5 -0.0529\n1.0 -0.0013\n"}),
    );
    assert_eq!(
        (status, a["points"].as_array().map(Vec::len)),
        (200, Some(5)),
        "{a}"
    );
}

#[test]
fn malformed_requests_get_json_errors_and_the_server_goes_on() {
    let (s, t, b) = request("POST", "/api/bezier", b"{not json");
    assert_json_error(s, &t, &b, 400, "malformed request");
    let (s, t, b) = request(
        "POST",
        "/api/bezier",
        br#"{"control_points": [[0, 0], [1, 1]], "t": 0.5, "extra": 1}"#,
    );
    assert_json_error(s, &t, &b, 400, "extra");
    let (s, t, b) = request(
        "POST",
        "/api/bezier",
        br#"{"control_points": [[0, 0], [1]], "t": 0.5}"#,
    );
    assert_json_error(s, &t, &b, 400, "malformed request");
    let (s, t, b) = request(
        "POST",
        "/api/bezier",
        br#"{"control_points": [[0, 0], [1, 1]], "t": 2}"#,
    );
    assert_json_error(s, &t, &b, 400, "outside");
    let (s, t, b) = request(
        "POST",
        "/api/approximate",
        br#"{"points": [[0, 0], [1, 1], [2, 0]], "degree": 3, "control_points": 9}"#,
    );
    assert_eq!(s, 400, "{b}");
    assert_json_error(s, &t, &b, 400, "");
    let (s, t, b) = request(
        "POST",
        "/api/bspline",
        br#"{"degree": 100000000000, "control_points": [[0, 0], [1, 1]]}"#,
    );
    assert_json_error(s, &t, &b, 400, "degree");
    let (s, t, b) = request("POST", "/api/approximate", br#"{"points": [[0, 0], [1, 1], [2, 0]], "degree": 2, "control_points": 3, "correct": 99999999}"#);
    assert_json_error(s, &t, &b, 400, "correct");
    let (s, t, b) = request("POST", "/api/features", br#"{"curve": {"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0, 0], [1, 1, 1]]}}"#);
    assert_json_error(s, &t, &b, 400, "planar");
    let (s, t, b) = request(
        "POST",
        "/api/load",
        br#"{"text": "not an airfoil\nat all\n"}"#,
    );
    assert_json_error(s, &t, &b, 400, "");
    let (s, t, b) = request("POST", "/api/nothing", b"{}");
    assert_json_error(s, &t, &b, 404, "unknown endpoint");
    let (s, t, b) = request("GET", "/api/bezier", b"");
    assert_json_error(s, &t, &b, 405, "POST");
    let (s, t, b) = request("GET", "/etc/passwd", b"");
    assert_json_error(s, &t, &b, 404, "not found");
    let big = vec![b' '; spline_studio::MAX_BODY + 1];
    let (s, t, b) = request("POST", "/api/load", &big);
    assert_json_error(s, &t, &b, 413, "at most");
    // Still serving.
    let (status, a) = post(
        "bezier",
        &json!({"control_points": [[0, 0], [2, 2]], "t": 0.5}),
    );
    assert_eq!((status, &a["point"]), (200, &json!([1.0, 1.0])));
}

#[test]
fn the_correction_report_carries_its_angle_error() {
    let points: Vec<[f64; 2]> = (0..30)
        .map(|k| {
            let t = f64::from(k) / 29.0 * std::f64::consts::PI;
            [t.cos(), 0.5 * t.sin()]
        })
        .collect();
    let (status, answer) = post(
        "approximate",
        &json!({"points": points, "degree": 3, "control_points": 6, "correct": 5}),
    );
    assert_eq!(status, 200, "{answer}");
    let c = &answer["correction"];
    let last = c["angles"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .as_f64()
        .unwrap();
    let error = c["angle_error"].as_f64().unwrap();
    assert_eq!(error, (std::f64::consts::FRAC_PI_2 - last).abs());
}
