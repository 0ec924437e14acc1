//! `spline studio`: serves the interactive page of `spline-studio` (the labs of seed 003).

use clap::Args;
use spline_core::{Error, Result};
use std::io::Write;

#[derive(Args)]
pub struct StudioArgs {
    /// Port to listen on (0: any free port; the address is printed).
    #[arg(long, default_value_t = 8765)]
    port: u16,
    /// Address to bind. The default serves this machine only; another address (0.0.0.0)
    /// lets other machines in — and compute on yours: only on a network you trust.
    #[arg(long, default_value = "127.0.0.1")]
    host: String,
}

/// Serves until the process is stopped; prints `{"url": "http://HOST:PORT/"}` on standard
/// output once the port is bound.
pub fn studio(args: &StudioArgs) -> Result<()> {
    let result = spline_studio::run(&args.host, args.port, |addr| {
        let mut out = std::io::stdout().lock();
        // The page's address, for a person and for scripts; the server runs on.
        let _ = writeln!(
            out,
            "{}",
            serde_json::json!({ "url": format!("http://{addr}/") })
        );
        let _ = out.flush();
    });
    result.map_err(|e| Error::io(format!("serve on {}:{}", args.host, args.port), e))
}
