//! The oracle of `rccpack ask --oracle CMD` (docs/guide.md#questions): a
//! command run on each probe's scene file whose exit status answers the
//! question; its whole process group is ended when it answers, fails,
//! times out or the person presses Ctrl-C.

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicI32, Ordering};
use std::time::{Duration, Instant};

/// The answer to one question.
pub(super) enum Verdict {
    Yes,
    No,
    Abort(String),
}

/// The process group of the oracle running now (0: none), for the Ctrl-C
/// handler.
static ORACLE_GROUP: AtomicI32 = AtomicI32::new(0);

/// End the oracle's whole process group (the shell and whatever it
/// started).
fn kill_group(pgid: i32) {
    #[cfg(unix)]
    if pgid > 0 {
        // SAFETY: sending a signal to a process group this process
        // created; no memory is involved.
        unsafe {
            libc::kill(-pgid, libc::SIGKILL);
        }
    }
    #[cfg(not(unix))]
    let _ = pgid;
}

pub(super) fn ask_oracle(cmd: &str, probe: &Path, timeout: Duration) -> Verdict {
    let mut command = Command::new("sh");
    command
        .arg("-c")
        .arg(format!("{cmd} \"$1\""))
        .arg("rccpack-ask")
        .arg(probe)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        // Its own process group: a hung oracle is ended whole.
        command.process_group(0);
    }
    let mut child = match command.spawn() {
        Ok(c) => c,
        Err(e) => return Verdict::Abort(format!("cannot run the oracle `{cmd}`: {e}")),
    };
    let pgid = i32::try_from(child.id()).unwrap_or(0);
    ORACLE_GROUP.store(pgid, Ordering::SeqCst);
    // Its standard error, read as it comes (a full pipe would hang it),
    // into a buffer the answer takes when the oracle exits: a child the
    // oracle left running in a session of its own (an image viewer) may
    // hold the pipe open for ever, and is never waited for.
    let said_so_far = std::sync::Arc::new(std::sync::Mutex::new(Vec::<u8>::new()));
    let (eof_tx, eof_rx) = std::sync::mpsc::channel::<()>();
    if let Some(mut e) = child.stderr.take() {
        let buf = said_so_far.clone();
        std::thread::spawn(move || {
            use std::io::Read as _;
            let mut chunk = [0u8; 4096];
            loop {
                match e.read(&mut chunk) {
                    Ok(0) | Err(_) => break,
                    Ok(k) => {
                        let mut b = buf.lock().unwrap_or_else(|p| p.into_inner());
                        let room = (1usize << 16).saturating_sub(b.len());
                        b.extend_from_slice(&chunk[..k.min(room)]);
                    }
                }
            }
            let _ = eof_tx.send(());
        });
    }
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Ok(s),
            Ok(None) if start.elapsed() >= timeout => {
                kill_group(pgid);
                let _ = child.kill();
                let _ = child.wait();
                ORACLE_GROUP.store(0, Ordering::SeqCst);
                return Verdict::Abort(format!(
                    "the oracle `{cmd}` gave no answer within {} s (--oracle-timeout); it was stopped",
                    timeout.as_secs_f64()
                ));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(10)),
            Err(e) => break Err(e),
        }
    };
    // Whatever the shell left running goes with it.
    kill_group(pgid);
    ORACLE_GROUP.store(0, Ordering::SeqCst);
    // What it printed: to the end of the pipe, or what came within a
    // moment when something outside its process group still holds it.
    let _ = eof_rx.recv_timeout(Duration::from_millis(200));
    let said = {
        let b = said_so_far.lock().unwrap_or_else(|p| p.into_inner());
        String::from_utf8_lossy(&b).trim().to_string()
    };
    oracle_verdict(cmd, status, &said)
}

/// What the oracle's exit status and standard error mean (docs/guide.md#questions): 0 is
/// acceptable (what it printed is passed on), 1 with nothing on standard
/// error not acceptable; 1 with an error (a mistyped rules path, a
/// crashed script) aborts, so a failure never confirms a rule.
fn oracle_verdict(
    cmd: &str,
    status: std::io::Result<std::process::ExitStatus>,
    said: &str,
) -> Verdict {
    if !said.is_empty() && !matches!(status.as_ref().map(|s| s.code()), Ok(Some(1))) {
        ewriteln!("{said}");
    }
    match status {
        Ok(s) => match s.code() {
            Some(0) => Verdict::Yes,
            Some(1) if said.is_empty() => Verdict::No,
            Some(1) => Verdict::Abort(format!(
                "the oracle `{}` exited with 1 and printed an error, so it failed rather than answered: {}; \
                 expected exit 1 with nothing on standard error for \"not acceptable\"",
                rccpack::limits::cut(cmd),
                rccpack::limits::cut(said)
            )),
            Some(c) => Verdict::Abort(format!(
                "the oracle `{cmd}` exited with {c}; expected 0 (acceptable) or 1 (not acceptable)"
            )),
            None => Verdict::Abort(format!("the oracle `{cmd}` was stopped by a signal")),
        },
        Err(e) => Verdict::Abort(format!("cannot run the oracle `{cmd}`: {e}")),
    }
}

/// End the oracle running now, if any (the Ctrl-C handler).
pub(super) fn kill_current() {
    kill_group(ORACLE_GROUP.load(Ordering::SeqCst));
}
