//! Exhaustive reference solver for tiny problems (tests only).
