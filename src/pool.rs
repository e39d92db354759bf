//! Running a pipeline on rayon's thread pool, with its progress reports on the calling thread.
//!
//! The stages are full of short parallel loops (a colour class of the area refinement, a
//! measure of the cells' masses: tens to thousands per run, each a few microseconds on a mesh
//! of a few thousand vertices). Started from a thread outside the pool, each loop is sent to
//! the pool and the caller sleeps until it is done, a round trip through the scheduler; from
//! a worker thread it is split in place and the other workers steal from it. So the library's
//! entry points ([`crate::parameterize`], [`crate::remesh()`], [`crate::harmonics::analyze`])
//! run on a worker thread, which makes the CLI about 10-15% faster on the small and mid-size
//! shared meshes (the largest are unchanged).
//!
//! A [`Progress`] may have to be called on the thread that started the work (MeshLab's
//! callback drives a Qt progress bar), so the reports are relayed: the worker sends each
//! report to the calling thread, which calls the caller's `progress` and sends its answer
//! (go on or cancel) back.

use crate::progress::{Progress, Stage};
use std::ops::ControlFlow;
use std::sync::mpsc;

/// Run `work` on a worker thread of rayon's current pool, calling `progress` on this thread
/// for each report `work` makes to the progress it is given. On a worker thread already,
/// `work` runs here with `progress` itself. A panic in `work` resumes on this thread.
pub(crate) fn on_pool<T: Send>(progress: &dyn Progress, work: impl FnOnce(&dyn Progress) -> T + Send) -> T {
    if rayon::current_thread_index().is_some() {
        return work(progress);
    }
    let (sender, receiver) = mpsc::channel::<Message<T>>();
    let done = rayon::in_place_scope(|scope| {
        scope.spawn(move |_| {
            let relay = Relay { sender: sender.clone() };
            let out = work(&relay);
            // The receiver lives until the scope ends; a failed send cannot happen.
            let _ = sender.send(Message::Done(out));
        });
        // Ends with `Done`, or with an error when `work` panicked (its sender dropped); the
        // scope then resumes the panic.
        let mut done = None;
        while let Ok(message) = receiver.recv() {
            match message {
                Message::Report { stage, fraction, text, answer } => {
                    let _ = answer.send(progress.report(stage, fraction, &text));
                }
                Message::Done(out) => {
                    done = Some(out);
                    break;
                }
            }
        }
        done
    });
    match done {
        Some(out) => out,
        // Unreachable: without `Done` the work panicked and the scope resumed the panic.
        None => unreachable!("the pool's work ended without a result or a panic"),
    }
}

/// What the worker sends the calling thread.
enum Message<T> {
    /// A progress report, and where its answer goes.
    Report { stage: Stage, fraction: f64, text: String, answer: mpsc::SyncSender<ControlFlow<()>> },
    /// The work's result.
    Done(T),
}

/// The worker's [`Progress`]: forwards each report and waits for the caller's answer.
struct Relay<T> {
    sender: mpsc::Sender<Message<T>>,
}

impl<T: Send> Progress for Relay<T> {
    fn report(&self, stage: Stage, fraction: f64, message: &str) -> ControlFlow<()> {
        let (answer, answered) = mpsc::sync_channel(1);
        let sent = self.sender.send(Message::Report { stage, fraction, text: message.to_owned(), answer });
        match sent.ok().and_then(|()| answered.recv().ok()) {
            Some(flow) => flow,
            // The calling thread is gone (it cannot be while it waits in `on_pool`): go on.
            None => ControlFlow::Continue(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;
    use std::thread;

    #[test]
    fn reports_reach_the_calling_thread_in_order_and_cancel_back() {
        let caller = thread::current().id();
        let seen = Mutex::new(Vec::new());
        let progress = |stage: Stage, fraction: f64, message: &str| {
            assert_eq!(thread::current().id(), caller, "report on another thread");
            seen.lock().unwrap().push((stage, fraction, message.to_owned()));
            if fraction >= 0.5 { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
        };
        let (worker, flows) = on_pool(&progress, |p| {
            let flows: Vec<ControlFlow<()>> = [0.0, 0.25, 0.5].iter().map(|&f| p.report(Stage::Transport, f, &format!("at {f}"))).collect();
            (rayon::current_thread_index(), flows)
        });
        assert!(worker.is_some(), "the work did not run on a worker thread");
        assert_eq!(flows, vec![ControlFlow::Continue(()), ControlFlow::Continue(()), ControlFlow::Break(())]);
        let seen = seen.into_inner().unwrap();
        assert_eq!(seen.len(), 3);
        assert_eq!(seen[2], (Stage::Transport, 0.5, "at 0.5".to_owned()));
    }

    #[test]
    fn on_a_worker_the_work_runs_in_place() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let (outer, inner) = pool.install(|| (rayon::current_thread_index(), on_pool(&crate::progress::NoProgress, |_| rayon::current_thread_index())));
        assert_eq!(outer, inner);
        assert!(inner.is_some());
    }

    #[test]
    fn a_panic_in_the_work_reaches_the_caller() {
        let caught = std::panic::catch_unwind(|| on_pool(&crate::progress::NoProgress, |_| -> usize { panic!("inside the pool") }));
        let payload = caught.expect_err("the panic was lost");
        let text = payload.downcast_ref::<&str>().copied().unwrap_or_default();
        assert_eq!(text, "inside the pool");
    }
}
