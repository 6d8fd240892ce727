//! The installation check's screens. Pure widgets over [`state::CheckView`]: the flow
//! (`crate::check`) changes the view, these draw it.

pub mod state;
