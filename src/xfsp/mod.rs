//! xfsp
