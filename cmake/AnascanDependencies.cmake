# Every dependency comes from Debian 12 packages (scripts/setup.sh installs them).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(nanoflann REQUIRED)
find_package(TBB REQUIRED)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(SQLite3 REQUIRED)
find_package(Threads REQUIRED)
find_package(OpenCV 4.5 REQUIRED COMPONENTS core imgproc imgcodecs calib3d)
find_package(Qhull REQUIRED)               # processing: convex hull of a stone (coverage)
find_package(Open3D REQUIRED)              # processing/surface: screened Poisson (Kazhdan port)
find_package(ZLIB REQUIRED)                 # drivers: CRC-32 of recorded frames
find_package(JPEG REQUIRED)                 # drivers: grey images (libjpeg-turbo), not imgcodecs
find_package(PNG REQUIRED)                  # drivers: grey images (libpng)
find_package(EXPAT REQUIRED)                # processing: the XML section of E57 files
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBUSB REQUIRED IMPORTED_TARGET GLOBAL libusb-1.0)  # drivers: USB backend
find_package(glfw3 3.3 REQUIRED)            # drivers: projector output window
find_package(OpenGL REQUIRED)
# Campaigns over MPI (Debian openmpi-bin, libopenmpi-dev), optional: without it the same
# campaign code runs in one process (acquisition/CMakeLists.txt).
option(ANASCAN_WITH_MPI "Campaigns over MPI when an MPI implementation is found" ON)
if(ANASCAN_WITH_MPI)
    find_package(MPI COMPONENTS CXX)
endif()
