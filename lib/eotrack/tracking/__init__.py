"""Tracking: Kalman filters, data association and track initiation."""
