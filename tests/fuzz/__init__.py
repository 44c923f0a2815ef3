"""Fuzz tests: hypothesis over the public surfaces, seeded and bounded to stay quick."""
