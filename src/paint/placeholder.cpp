// Placeholder translation unit; replaced as the paint area lands.
namespace adaptex {}
