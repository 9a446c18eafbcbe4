"""Pose: PnP, DLT, RANSAC pose, Fisher information / CRLB of a pose, feature selection."""
