"""pytest's configuration for the course's tests; shared helpers live in notebook_runner.py."""
