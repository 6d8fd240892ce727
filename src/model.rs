//! What we know about the unit, each fact with the time we learned it.
