# acquisition/store: the session store: SQLite database, crash-safe scan files, checks and JSON views.
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/store/codec.cpp
    src/store/db.cpp
    src/store/groups.cpp
    src/store/scan_files.cpp
    src/store/scans.cpp
    src/store/schema.cpp
    src/store/session_check.cpp
    src/store/session_json.cpp
    src/store/session_store.cpp
    src/store/session_truth.cpp
)
