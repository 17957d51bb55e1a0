"""Launch-monitor sessions and shot tables, read as exported (one room: the readers).

The public entry is :func:`read_session` (and :class:`Session`, what it returns); :func:`fly_session` flies a session's
shots beside what the monitor reported. The modules below are this subpackage's own: names with a leading underscore
are private to it and are never imported from outside ``impactlab.data.sessions``.
"""

from impactlab.data.sessions.reader import DATASETS, Session, dataset_path, read_session, read_session_text

__all__ = ["DATASETS", "Session", "dataset_path", "read_session", "read_session_text"]
