//! Wang–Wang–Kim (2001) algebraic separation test (to be written).
