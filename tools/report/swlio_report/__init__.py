"""swlio-report: one self-contained HTML page that says what happened in an incident, a
recording or the daemon's log directory (docs/report.md)."""
