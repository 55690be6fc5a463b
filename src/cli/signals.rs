//! SIGINT (Ctrl-C), SIGTERM and SIGHUP for every command but `studio`
//! (which stops gracefully on its own): one handler for the process
//! (`ctrlc` with its `termination` feature), installed at start-up.
//!
//! A command that can stop cleanly registers what to do with [`on_signal`]
//! (`synth` and `sample` stop the search and write what they found; `ask`
//! ends its oracle and says what is saved). Every other command ends at
//! once, exit 1, after removing the temporary files of the writes going on
//! ([`rccpack::fsutil::remove_in_flight`]): the targets keep their previous
//! contents and nothing half-written is left beside them.

use std::sync::Mutex;

type Action = Box<dyn Fn() + Send>;

static ACTION: Mutex<Option<Action>> = Mutex::new(None);

/// Install the handler (once, before the command runs).
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        let action = ACTION.lock().unwrap_or_else(|e| e.into_inner());
        match &*action {
            Some(f) => f(),
            None => {
                rccpack::fsutil::remove_in_flight();
                ewriteln!("error: interrupted by a signal; no file was left half-written");
                std::process::exit(1);
            }
        }
    });
}

/// What a signal does from now on, instead of ending the process.
pub fn on_signal(f: impl Fn() + Send + 'static) {
    *ACTION.lock().unwrap_or_else(|e| e.into_inner()) = Some(Box::new(f));
}
