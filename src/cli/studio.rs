use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;
use std::process::ExitCode;

/// `rccpack studio DIR [--port P] [--open] [--priors PRIORS.json]`
///
/// Serve the studio page for the task folder DIR on 127.0.0.1 only.
#[derive(Args, Debug)]
pub struct StudioArgs {
    /// Task folder: `problem.json`, `demos.json` (created when absent),
    /// optional `statements.rcc`; the page writes `learned.rcc` there.
    dir: PathBuf,
    /// Port on 127.0.0.1 (0: any free port; the URL is printed).
    #[arg(long, default_value_t = 0)]
    port: u16,
    /// Open the page in the default browser.
    #[arg(long)]
    open: bool,
    /// Priors learned across tasks (`rccpack priors`) for every learning
    /// run of the studio (Learn and Check rules).
    #[arg(long, value_name = "PRIORS.json")]
    priors: Option<PathBuf>,
}

pub fn run(a: StudioArgs) -> Result<ExitCode> {
    let priors = super::priors::read_priors_opt(a.priors.as_deref())?.map(std::sync::Arc::new);
    let app = rccpack::studio::router_with(&a.dir, rccpack::studio::StudioOptions { priors })
        .map_err(|e| super::Reported(format!("error: {e}")))?;
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    let served = rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind(("127.0.0.1", a.port))
            .await
            .with_context(|| format!("cannot listen on 127.0.0.1:{}", a.port))?;
        let url = format!("http://{}/", listener.local_addr()?);
        super::outln(format!("rccpack studio: {} at {url}", a.dir.display()))?;
        super::outln("press Ctrl-C to stop")?;
        if a.open {
            if let Err(e) = std::process::Command::new("xdg-open").arg(&url).spawn() {
                ewriteln!("warning: cannot open a browser ({e}); open {url} yourself");
            }
        }
        axum::serve(listener, app)
            .with_graceful_shutdown(stop_signal())
            .await
            .context("server error")?;
        Ok(ExitCode::SUCCESS)
    });
    // Do not wait for a long solve still running on a blocking thread.
    rt.shutdown_timeout(std::time::Duration::from_millis(500));
    rccpack::fsutil::remove_in_flight();
    served
}

/// Ctrl-C, SIGTERM or SIGHUP: the server stops taking requests and lets
/// the ones going on finish their writes (no temporary file is left).
async fn stop_signal() {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        let term = signal(SignalKind::terminate());
        let hup = signal(SignalKind::hangup());
        if let (Ok(mut term), Ok(mut hup)) = (term, hup) {
            tokio::select! {
                _ = tokio::signal::ctrl_c() => {}
                _ = term.recv() => {}
                _ = hup.recv() => {}
            }
            return;
        }
    }
    let _ = tokio::signal::ctrl_c().await;
}
