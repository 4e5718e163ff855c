// Compiled parts of paper 004's models (placeholder: filled by the model's implementation).
namespace gyrostat {}
