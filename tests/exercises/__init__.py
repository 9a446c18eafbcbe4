"""Exercise-checker tests (a package, so their basenames may repeat tests/papers/)."""
