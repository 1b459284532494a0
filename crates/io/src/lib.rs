//! Problem and result I/O (work in progress).
