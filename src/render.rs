//! Pictures of scenes: SVG, and PNG through resvg.
