"""The diagnosis of pin-on-disc (tribometer) tests: measured wear volumes against plain Archard,
a catalogue of departures from it, and the extended [wear] section."""
