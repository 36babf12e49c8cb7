# acquisition/campaign: the campaign store (SQLite), the job's stages as tasks, executors.
list(APPEND ANASCAN_ACQUISITION_SOURCES
    src/campaign/campaign_check.cpp
    src/campaign/campaign_job.cpp
    src/campaign/campaign_json.cpp
    src/campaign/campaign_results.cpp
    src/campaign/campaign_rows.cpp
    src/campaign/campaign_status.cpp
    src/campaign/campaign_store.cpp
    src/campaign/campaign_tasks.cpp
    src/campaign/stone_stages.cpp
)
