//! `spline studio` through the binary: it prints its URL as JSON, serves the page and the
//! endpoints on loopback, and refuses a bad address with the one-line error contract.

#![cfg(feature = "studio")]

use crate::common;

use common::spline;
use serde_json::Value;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

/// The server, stopped by its process id when the test ends.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn http(addr: &str, request: &str) -> String {
    let mut stream = TcpStream::connect(addr).expect("connect");
    stream.write_all(request.as_bytes()).expect("write");
    let mut answer = String::new();
    stream.read_to_string(&mut answer).expect("read");
    answer
}

#[test]
fn studio_prints_its_url_and_serves_the_page_on_loopback() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_spline"))
        .args(["studio", "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run spline studio");
    let stdout = child.stdout.take().expect("stdout");
    let server = Server(child);
    let mut line = String::new();
    BufReader::new(stdout).read_line(&mut line).expect("a line");
    let url: Value = serde_json::from_str(&line).expect("JSON on stdout");
    let url = url["url"].as_str().expect("a url").to_owned();
    let addr = url
        .strip_prefix("http://")
        .and_then(|s| s.strip_suffix('/'))
        .expect("http://HOST:PORT/");
    assert!(
        addr.starts_with("127.0.0.1:"),
        "loopback by default: {addr}"
    );
    let page = http(
        addr,
        "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
    );
    assert!(page.starts_with("HTTP/1.1 200") && page.contains("spline studio"));
    let body = r#"{"control_points": [[0, 0], [1, 1], [2, 0]], "t": 0.5}"#;
    let answer = http(
        addr,
        &format!(
            "POST /api/bezier HTTP/1.1\r\nHost: x\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
            body.len()
        ),
    );
    assert!(answer.contains(r#""point":[1.0,0.5]"#), "{answer}");
    drop(server);
}

#[test]
fn studio_on_a_bad_address_is_a_one_line_error() {
    let message = spline(&["studio", "--host", "256.1.1.1", "--port", "0"]).assert_clean_error();
    assert!(message.contains("256.1.1.1"), "{message}");
    let message = spline(&["studio", "--port", "70000"]).assert_clean_error();
    assert!(message.contains("70000"), "{message}");
}
