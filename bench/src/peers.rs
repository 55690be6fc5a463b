//! Other solvers on the same model, for side-by-side measurement
//! (`rccpack-bench thesis --peers`): OR-Tools CP-SAT and MiniZinc with
//! Gecode, each run on the model [`rccpack::synth::emit`] writes.
//!
//! Each peer is a small script in `benches/peers/` (found through
//! `CARGO_MANIFEST_DIR`, so a binary moved away from its source tree has
//! none), run with `python3`:
//!
//! - `cpsat.py MODEL.json --time-limit S [--workers N]` builds a CP-SAT
//!   model from the `rccpack-model/1` JSON form;
//! - `minizinc.py MODEL.mzn --time-limit S [--workers N]` runs
//!   `minizinc --solver gecode` on the MiniZinc form.
//!
//! Both print one JSON line on stdout:
//! `{"status": "optimal"|"feasible"|"infeasible"|"unknown", "values": [..] or
//! null, "objective": int or null, "time_s": float}` (`values`: one grid
//! value per model variable; `objective`: the integer score numerator,
//! constant terms included, see [`rccpack::synth::emit`]).
//!
//! [`solve`] writes the model to a temporary file, runs the script, checks
//! the answer's shape (values in the variables' domains) and returns it;
//! every failure is an `Err` naming the peer, with the tail of its stderr.
//! The caller re-checks a layout with `rccpack::synth::verify_solution` and
//! re-scores it with the evaluator like any other.

use super::BenchError;
use rccpack::synth::emit::{to_json, to_minizinc, Emitted};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// A peer solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Peer {
    /// Google OR-Tools CP-SAT (Python package `ortools`).
    CpSat,
    /// Gecode through MiniZinc (`minizinc --solver gecode`).
    Gecode,
}

impl Peer {
    /// Every peer.
    pub const ALL: [Peer; 2] = [Peer::CpSat, Peer::Gecode];

    /// Its name in tables and messages: `cp-sat`, `gecode`.
    pub fn name(self) -> &'static str {
        match self {
            Peer::CpSat => "cp-sat",
            Peer::Gecode => "gecode",
        }
    }

    /// Its script in `benches/peers/`.
    pub fn script(self) -> &'static Path {
        Path::new(match self {
            Peer::CpSat => concat!(env!("CARGO_MANIFEST_DIR"), "/../benches/peers/cpsat.py"),
            Peer::Gecode => concat!(env!("CARGO_MANIFEST_DIR"), "/../benches/peers/minizinc.py"),
        })
    }

    /// The model file's extension it reads.
    fn extension(self) -> &'static str {
        match self {
            Peer::CpSat => "json",
            Peer::Gecode => "mzn",
        }
    }
}

impl std::fmt::Display for Peer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Peer {
    type Err = String;
    fn from_str(s: &str) -> Result<Peer, String> {
        match s {
            "cp-sat" | "cpsat" => Ok(Peer::CpSat),
            "gecode" => Ok(Peer::Gecode),
            _ => Err(format!("unknown peer `{s}`; expected `cp-sat` or `gecode`")),
        }
    }
}

/// How a peer's solve ended (the same meaning as [`rccpack::synth::Status`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PeerStatus {
    /// Proved optimal.
    Optimal,
    /// A limit stopped the search; the layout is the best found.
    Feasible,
    /// No layout keeps the hard rules.
    Infeasible,
    /// A limit stopped the search before any layout.
    Unknown,
}

/// A peer's answer.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PeerResult {
    /// How it ended.
    pub status: PeerStatus,
    /// Grid values, one per model variable (with `optimal`/`feasible`).
    pub values: Option<Vec<i64>>,
    /// The integer objective of `values` as the peer reports it (constant
    /// terms included).
    pub objective: Option<i64>,
    /// The solve time the peer reports (`time_s`), in milliseconds.
    pub time_ms: f64,
    /// Wall time around the whole process (interpreter start, model
    /// loading, solve), in milliseconds.
    pub process_ms: f64,
}

/// The JSON line a peer script prints.
#[derive(serde::Deserialize)]
struct Line {
    status: String,
    values: Option<Vec<i64>>,
    objective: Option<i64>,
    time_s: f64,
}

/// Run `cmd` with its output captured; `None` when it cannot be started.
fn output_of(cmd: &mut Command) -> Option<std::process::Output> {
    cmd.stdin(Stdio::null()).output().ok()
}

/// Whether `peer` can run here; the error says what is missing and how to
/// install it.
pub fn check_available(peer: Peer) -> Result<(), BenchError> {
    availability(peer).map_err(BenchError::PeerUnavailable)
}

fn availability(peer: Peer) -> Result<(), String> {
    let script = peer.script();
    if !script.is_file() {
        return Err(format!(
            "{peer}: the script {} is missing (peers run from a source checkout)",
            script.display()
        ));
    }
    match output_of(Command::new("python3").arg("--version")) {
        Some(o) if o.status.success() => {}
        _ => {
            return Err(format!(
                "{peer}: `python3` is not on PATH; install Python 3 (Debian: `apt-get install python3`)"
            ))
        }
    }
    match peer {
        Peer::CpSat => match output_of(Command::new("python3").args(["-c", "import ortools"])) {
            Some(o) if o.status.success() => Ok(()),
            _ => Err(format!(
                "{peer}: the Python package `ortools` is missing; install it with `pip install ortools`"
            )),
        },
        Peer::Gecode => match output_of(Command::new("minizinc").arg("--solvers")) {
            None => Err(format!(
                "{peer}: `minizinc` is not on PATH; install it (Debian: `apt-get install minizinc`, which brings Gecode)"
            )),
            Some(o) => {
                let text = String::from_utf8_lossy(&o.stdout).to_lowercase();
                if o.status.success() && text.contains("gecode") {
                    Ok(())
                } else {
                    Err(format!(
                        "{peer}: `minizinc` has no Gecode solver; install it (Debian: `apt-get install minizinc`, which brings Gecode)"
                    ))
                }
            }
        },
    }
}

static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A model file in the temporary folder, removed when dropped.
struct TempModel(PathBuf);

impl TempModel {
    fn write(ext: &str, text: &str) -> Result<TempModel, String> {
        let n = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
        let path =
            std::env::temp_dir().join(format!("rccpack-peer-{}-{n}.{ext}", std::process::id()));
        rccpack::fsutil::atomic_write(&path, text)
            .map_err(|e| format!("cannot write the model to {}: {e}", path.display()))?;
        Ok(TempModel(path))
    }
}

impl Drop for TempModel {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// The last `n` lines of `text`.
fn tail(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// How long past its time limit a peer may run before it is killed (start
/// up, model loading, a solver that overruns its limit).
const GRACE: Duration = Duration::from_secs(60);

/// Solve `e` with `peer` on one worker under `time_limit`.
pub fn solve(peer: Peer, e: &Emitted, time_limit: Duration) -> Result<PeerResult, BenchError> {
    solve_with(peer, e, time_limit, 1)
}

/// [`solve`] with `workers` search threads (CP-SAT's `num_workers`,
/// Gecode's `-p`).
pub fn solve_with(
    peer: Peer,
    e: &Emitted,
    time_limit: Duration,
    workers: u32,
) -> Result<PeerResult, BenchError> {
    run_peer(peer, e, time_limit, workers).map_err(BenchError::PeerFailed)
}

/// Run `peer`'s script on `e` and read its answer.
fn run_peer(
    peer: Peer,
    e: &Emitted,
    time_limit: Duration,
    workers: u32,
) -> Result<PeerResult, String> {
    let text = match peer {
        Peer::CpSat => to_json(e),
        Peer::Gecode => to_minizinc(e),
    };
    let model = TempModel::write(peer.extension(), &text).map_err(|m| format!("{peer}: {m}"))?;
    let run = run_script(peer, &model.0, time_limit, workers)?;
    read_answer(peer, e, &run)
}

/// What a peer's script did: its output, how it ended, how long it ran.
struct ScriptRun {
    /// Everything it printed on stdout.
    stdout: String,
    /// Everything it printed on stderr.
    stderr: String,
    /// How it exited (`None`: the process was lost).
    status: Option<ExitStatus>,
    /// Killed at the deadline (time limit plus [`GRACE`]).
    killed: bool,
    /// Wall time of the process, ms.
    process_ms: f64,
}

/// Start `peer`'s script on the model file and wait for it, reading both
/// pipes on their own threads (a full pipe would block the child), and
/// killing it at the deadline.
fn run_script(
    peer: Peer,
    model: &Path,
    time_limit: Duration,
    workers: u32,
) -> Result<ScriptRun, String> {
    let start = Instant::now();
    let mut child = Command::new("python3")
        .arg(peer.script())
        .arg(model)
        .arg("--time-limit")
        .arg(format!("{}", time_limit.as_secs_f64()))
        .arg("--workers")
        .arg(workers.max(1).to_string())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|err| format!("{peer}: cannot run python3: {err}"))?;
    let out_t = read_all(child.stdout.take());
    let err_t = read_all(child.stderr.take());
    let deadline = start + time_limit.saturating_add(GRACE);
    let mut killed = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if Instant::now() >= deadline => {
                let _ = child.kill();
                killed = true;
                break child.wait().ok();
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(2)),
            Err(_) => break None,
        }
    };
    let process_ms = start.elapsed().as_secs_f64() * 1000.0;
    Ok(ScriptRun {
        stdout: String::from_utf8_lossy(&out_t.join().unwrap_or_default()).into_owned(),
        stderr: String::from_utf8_lossy(&err_t.join().unwrap_or_default()).into_owned(),
        status,
        killed,
        process_ms,
    })
}

/// Read `pipe` to its end on a thread of its own.
fn read_all<R: Read + Send + 'static>(mut pipe: Option<R>) -> std::thread::JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut s = Vec::new();
        if let Some(p) = pipe.as_mut() {
            let _ = p.read_to_end(&mut s);
        }
        s
    })
}

/// The answer of a script run: its last non-empty line of stdout as a
/// [`Line`], checked (a known status, values for every variable within
/// its domain when there is a solution, a finite time). Errors end with
/// the last lines of its stderr.
fn read_answer(peer: Peer, e: &Emitted, run: &ScriptRun) -> Result<PeerResult, String> {
    let fail = |what: String| {
        let t = tail(&run.stderr, 10);
        if t.trim().is_empty() {
            format!("{peer}: {what}")
        } else {
            format!("{peer}: {what}; stderr:\n{t}")
        }
    };
    if run.killed {
        return Err(fail(format!(
            "still running {} s past its time limit, killed",
            GRACE.as_secs()
        )));
    }
    match run.status {
        Some(s) if s.success() => {}
        Some(s) => return Err(fail(format!("the script failed ({s})"))),
        None => return Err(fail("lost the script's process".into())),
    }
    let Some(last) = run.stdout.lines().rev().find(|l| !l.trim().is_empty()) else {
        return Err(fail("the script printed nothing".into()));
    };
    let line: Line = serde_json::from_str(last)
        .map_err(|err| fail(format!("cannot read its answer `{}`: {err}", clip(last))))?;
    let status = match line.status.as_str() {
        "optimal" => PeerStatus::Optimal,
        "feasible" => PeerStatus::Feasible,
        "infeasible" => PeerStatus::Infeasible,
        "unknown" => PeerStatus::Unknown,
        other => return Err(fail(format!("unknown status `{}`", clip(other)))),
    };
    let has_solution = matches!(status, PeerStatus::Optimal | PeerStatus::Feasible);
    let values = match (has_solution, line.values) {
        (true, Some(v)) => Some(in_domains(v, e).map_err(fail)?),
        (true, None) => return Err(fail(format!("status {} without values", line.status))),
        (false, _) => None,
    };
    if !line.time_s.is_finite() || line.time_s < 0.0 {
        return Err(fail(format!("time_s {} is not a duration", line.time_s)));
    }
    Ok(PeerResult {
        status,
        values,
        objective: if has_solution { line.objective } else { None },
        time_ms: line.time_s * 1000.0,
        process_ms: run.process_ms,
    })
}

/// `v` when it has one value per variable of `e`'s model, each within its
/// domain.
fn in_domains(v: Vec<i64>, e: &Emitted) -> Result<Vec<i64>, String> {
    let vars = &e.model.vars;
    if v.len() != vars.len() {
        return Err(format!("{} values for {} variables", v.len(), vars.len()));
    }
    if let Some((i, x)) = v
        .iter()
        .enumerate()
        .find(|&(i, &x)| !(0..=vars[i].ub).contains(&x))
    {
        return Err(format!(
            "value {x} of variable {i} is outside its domain 0..={}",
            vars[i].ub
        ));
    }
    Ok(v)
}

/// At most 200 characters of `s`, for messages.
fn clip(s: &str) -> String {
    let mut out: String = s.chars().take(200).collect();
    if out.len() < s.len() {
        out.push('…');
    }
    out
}
