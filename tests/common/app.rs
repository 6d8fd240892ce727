//! The page (`App`) pumped on the real clock, as its own loop runs it.

use std::time::{Duration, Instant};

use vpx_efis::app::App;

/// Pumps `app` until `f` holds, and says when it did; fails after `limit` naming
/// `what` (and the check's prompt, where a check is open).
pub fn until(
    app: &mut App,
    what: &str,
    limit: Duration,
    f: impl Fn(&App, Instant) -> bool,
) -> Instant {
    let end = Instant::now() + limit;
    loop {
        let now = Instant::now();
        if f(app, now) {
            return now;
        }
        assert!(
            now < end,
            "timed out waiting for {what}: {:#?}",
            app.check_view().prompt
        );
        app.pump_until(now + Duration::from_millis(20));
    }
}

/// How many frames of the message `name` the page has written.
pub fn sent(app: &App, name: &str) -> u64 {
    app.model().link.tx.get(name).map_or(0, |s| s.count)
}
