//! What a long plan is doing, for a front end to show (the command line's spinner): the stage,
//! and for stages of many parts how many are done. A 300 ha farm takes a minute to plan and
//! check, and "planning 30 field(s)" for 45 s said nothing of how far along it was (decision
//! 0038). The sink is process-wide and set by the front end; by default there is none and the
//! library prints nothing.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Where the stages go: the front end's display.
pub type Sink = Box<dyn Fn(&str) + Send + Sync>;

static SINK: Mutex<Option<Sink>> = Mutex::new(None);

/// Sends the stages to `sink` from now on (`None`: nowhere).
pub fn set_sink(sink: Option<Sink>) {
    *SINK
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner) = sink;
}

/// Tells the sink, if any, the stage `stage` gives (formatted only when there is one).
pub fn stage(stage: impl FnOnce() -> String) {
    let sink = SINK
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(sink) = sink.as_ref() {
        sink(&stage());
    }
}

/// A stage of `total` parts done in any order, on any thread: "`what`: 12 of 30".
pub struct Counter {
    what: &'static str,
    total: usize,
    done: AtomicUsize,
}

impl Counter {
    /// The stage begun: none of `total` done.
    pub fn new(what: &'static str, total: usize) -> Self {
        stage(|| format!("{what}: 0 of {total}"));
        Self {
            what,
            total,
            done: AtomicUsize::new(0),
        }
    }

    /// One more part done.
    pub fn one_done(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        stage(|| format!("{}: {done} of {}", self.what, self.total));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn a_counter_reports_each_part_done_to_the_sink() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let into = Arc::clone(&seen);
        set_sink(Some(Box::new(move |stage: &str| {
            into.lock().unwrap().push(stage.to_string());
        })));
        let counter = Counter::new("testing the progress counter", 3);
        std::thread::scope(|scope| {
            for _ in 0..3 {
                scope.spawn(|| counter.one_done());
            }
        });
        set_sink(None);
        // Other tests may report stages meanwhile: only this counter's are looked at.
        let ours: Vec<String> = seen
            .lock()
            .unwrap()
            .iter()
            .filter(|stage| stage.starts_with("testing the progress counter"))
            .cloned()
            .collect();
        assert_eq!(ours.len(), 4, "{ours:?}");
        assert_eq!(ours[0], "testing the progress counter: 0 of 3");
        let mut counts: Vec<&str> = ours[1..]
            .iter()
            .filter_map(|stage| stage.strip_prefix("testing the progress counter"))
            .collect();
        counts.sort_unstable();
        assert_eq!(counts, [": 1 of 3", ": 2 of 3", ": 3 of 3"]);
        // No sink: nothing is formatted.
        stage(|| unreachable!("formatted with no sink"));
    }
}
