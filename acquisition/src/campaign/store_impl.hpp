#pragma once
// CampaignStore's state, shared by its source files.
#include <filesystem>

#include "anascan/acquisition/campaign/campaign_store.hpp"
#include "store/db.hpp"

namespace anascan::acquisition {

struct CampaignStore::Impl {
    std::filesystem::path dir;
    db::Connection db;
    int lock_fd = -1;
    ~Impl();
};

}  // namespace anascan::acquisition
