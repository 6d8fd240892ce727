//! The installation check: every switch input, circuit and motor tested in turn, an
//! electrical load analysis, and a report for the builder's log. A flow like `setup`:
//! keys and ticks in, the view (`ui::check::state::CheckView`) changed and what the app
//! must send out. Pure and driven on the caller's clock; the app only wires it to the
//! link, the page's controller (so every motor rule and stop cause applies) and the
//! terminal.
