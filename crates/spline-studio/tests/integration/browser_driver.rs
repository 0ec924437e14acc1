//! The browser test's driver: Chromium and chromedriver started and stopped, the page's
//! state and drawn paths read back in world coordinates, mouse and keyboard actions.

use fantoccini::actions::{InputSource, MouseActions, PointerAction};
use fantoccini::{Client, ClientBuilder, Locator};
use nalgebra::Vector2;
use serde_json::{Value, json};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::PathBuf;
use std::process::Child;
use std::time::{Duration, Instant};
pub(super) type P = Vector2<f64>;
pub(super) type TestResult<T = ()> = Result<T, Box<dyn std::error::Error + Send + Sync>>;

/// Chromium's flags: headless, and no background connections (the network is closed).
pub(super) const CHROMIUM_ARGS: &[&str] = &[
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
    "--window-size=1300,1000",
];

/// chromedriver, stopped (by its process id) when the test ends, passed or not.
pub(super) struct Driver(pub(super) Child);

impl Drop for Driver {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

pub(super) fn free_port() -> TestResult<u16> {
    Ok(TcpListener::bind("127.0.0.1:0")?.local_addr()?.port())
}

pub(super) fn target_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .map_or_else(|| PathBuf::from("target"), PathBuf::from)
}

pub(super) fn start_studio() -> SocketAddr {
    crate::http::server()
}

pub(super) async fn connect(port: u16, profile: &std::path::Path) -> TestResult<Client> {
    let mut args: Vec<String> = CHROMIUM_ARGS.iter().map(|s| (*s).to_owned()).collect();
    args.push(format!("--user-data-dir={}", profile.display()));
    let mut caps = serde_json::Map::new();
    caps.insert("browserName".into(), json!("chrome"));
    caps.insert(
        "goog:chromeOptions".into(),
        json!({ "binary": "/usr/bin/chromium", "args": args }),
    );
    let deadline = Instant::now() + Duration::from_secs(30);
    while TcpStream::connect(("127.0.0.1", port)).is_err() {
        if Instant::now() > deadline {
            return Err("chromedriver did not start".into());
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let connector = hyper_util::client::legacy::connect::HttpConnector::new();
    Ok(ClientBuilder::new(connector)
        .capabilities(caps)
        .connect(&format!("http://127.0.0.1:{port}"))
        .await?)
}

/// Waits until the page has drawn every answer it asked for (and at least `renders`).
pub(super) async fn idle(c: &Client, renders: u64) -> TestResult<Value> {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let state = c
            .execute(
                "return window.studio ? {idle: studio.idle(), renders: studio.renders, \
                 error: document.getElementById('error').textContent} : null",
                vec![],
            )
            .await?;
        if state["idle"] == json!(true) && state["renders"].as_u64().unwrap_or(0) >= renders {
            return Ok(state);
        }
        if Instant::now() > deadline {
            return Err(format!("the page did not settle: {state}").into());
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

pub(super) async fn renders(c: &Client) -> TestResult<u64> {
    Ok(c.execute("return studio.renders", vec![])
        .await?
        .as_u64()
        .unwrap_or(0))
}

/// Runs `action`, then waits for the page to draw its consequences without error.
pub(super) async fn settle(c: &Client, before: u64) -> TestResult {
    let state = idle(c, before + 1)
        .await
        .map_err(|e| format!("{e} (waiting for render {})", before + 1))?;
    assert_eq!(state["error"], json!(""), "the page shows an error");
    Ok(())
}

pub(super) async fn js(c: &Client, script: &str) -> TestResult<Value> {
    Ok(c.execute(script, vec![]).await?)
}

/// The top-left corner of the drawing area in viewport pixels.
pub(super) async fn canvas_origin(c: &Client) -> TestResult<(f64, f64)> {
    let r = js(
        c,
        "const c = document.getElementById('canvas'); const r = c.getBoundingClientRect(); \
         return [r.left + c.clientLeft, r.top + c.clientTop];",
    )
    .await?;
    Ok((r[0].as_f64().unwrap_or(0.0), r[1].as_f64().unwrap_or(0.0)))
}

pub(super) fn mouse(actions: Vec<PointerAction>) -> MouseActions {
    actions
        .into_iter()
        .fold(MouseActions::new("mouse".into()), InputSource::then)
}

pub(super) fn move_to(x: f64, y: f64) -> PointerAction {
    PointerAction::MoveTo {
        duration: Some(Duration::from_millis(20)),
        x: x.round(),
        y: y.round(),
    }
}

pub(super) async fn click_at(c: &Client, x: f64, y: f64, button: u64) -> TestResult {
    let before = renders(c).await?;
    c.perform_actions(mouse(vec![
        move_to(x, y),
        PointerAction::Down { button },
        PointerAction::Up { button },
    ]))
    .await?;
    settle(c, before).await
}

pub(super) async fn click(c: &Client, css: &str) -> TestResult {
    let before = renders(c).await?;
    c.find(Locator::Css(css)).await?.click().await?;
    settle(c, before)
        .await
        .map_err(|e| format!("after a click on {css}: {e}").into())
}

/// Sets a control's value and fires its events, as a person typing would.
pub(super) async fn set_value(c: &Client, id: &str, value: &str) -> TestResult {
    let before = renders(c).await?;
    js(
        c,
        &format!(
            "const e = document.getElementById('{id}'); e.value = '{value}'; \
             e.dispatchEvent(new Event('input')); e.dispatchEvent(new Event('change'));"
        ),
    )
    .await?;
    settle(c, before).await
}

pub(super) fn to_points(value: &Value) -> Vec<P> {
    value
        .as_array()
        .map(|a| {
            a.iter()
                .map(|p| {
                    P::new(
                        p[0].as_f64().unwrap_or(f64::NAN),
                        p[1].as_f64().unwrap_or(f64::NAN),
                    )
                })
                .collect()
        })
        .unwrap_or_default()
}

pub(super) async fn state_points(c: &Client) -> TestResult<Vec<P>> {
    Ok(to_points(&js(c, "return studio.state.points").await?))
}

/// The vertices of a drawn path (`M x y L x y …`, world coordinates).
pub(super) async fn path(c: &Client, id: &str) -> TestResult<Vec<P>> {
    let d = c
        .find(Locator::Id(id))
        .await?
        .attr("d")
        .await?
        .ok_or("path without d")?;
    let numbers: Vec<f64> = d
        .split(|ch: char| ch == 'M' || ch == 'L' || ch.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    Ok(numbers.chunks(2).map(|xy| P::new(xy[0], xy[1])).collect())
}

/// The drawn path matches the library's points, vertex by vertex.
pub(super) fn assert_drawn(drawn: &[P], expected: &[P], what: &str) {
    assert_eq!(drawn.len(), expected.len(), "{what}: number of vertices");
    let worst = drawn
        .iter()
        .zip(expected)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0f64, f64::max);
    assert!(
        worst < 1e-12,
        "{what}: drawn path off the library's curve by {worst:e}"
    );
}

pub(super) fn world(origin: (f64, f64), pixel: (f64, f64)) -> P {
    // The page's initial view: 500 pixels per unit, world origin at pixel (60, 520), y up.
    P::new(
        (pixel.0 - origin.0 - 60.0) / 500.0,
        (520.0 - (pixel.1 - origin.1)) / 500.0,
    )
}

pub(super) async fn screenshot(c: &Client, name: &str) -> TestResult<PathBuf> {
    let dir = target_dir().join("studio");
    std::fs::create_dir_all(&dir)?;
    let file = dir.join(name);
    std::fs::write(&file, c.screenshot().await?)?;
    println!("screenshot: {}", file.display());
    Ok(file)
}
