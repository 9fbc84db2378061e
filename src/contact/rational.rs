//! Contact function through its rational form (to be written).
