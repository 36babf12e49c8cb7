# acquisition/capture: the capture session: scanner, persistence and registration threads, device calls.
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/capture/capture_session.cpp
    src/capture/device.cpp
    src/capture/device_settings_form.cpp
    src/capture/register.cpp
    src/capture/save.cpp
    src/capture/scanner.cpp
    src/capture/stone_check.cpp
)
