// Compiled parts of paper 003's models (placeholder: filled by the model's implementation).
namespace gyrostat {}
