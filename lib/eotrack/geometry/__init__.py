"""Geometry: rotations, pinhole cameras, intrinsics, distortion, epipolar geometry, triangulation."""
