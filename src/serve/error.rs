//! The API's error answer: a status, a message and the request field it is about, as JSON.

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde_json::json;

/// An error answer: a status, a message, and the request field it is about.
#[derive(Debug)]
pub struct ApiError {
    status: StatusCode,
    field: Option<String>,
    message: String,
}

impl ApiError {
    /// 400: the request is malformed.
    pub fn bad(field: &str, message: String) -> ApiError {
        ApiError { status: StatusCode::BAD_REQUEST, field: Some(field.into()), message }
    }
    /// 403: a path outside the root.
    pub fn forbidden(field: &str, message: String) -> ApiError {
        ApiError { status: StatusCode::FORBIDDEN, field: Some(field.into()), message }
    }
    /// 404: no such thing.
    pub fn not_found(field: &str, message: String) -> ApiError {
        ApiError { status: StatusCode::NOT_FOUND, field: Some(field.into()), message }
    }
    /// 422: a spec (or setting) the checks refuse.
    pub fn invalid(field: Option<String>, message: String) -> ApiError {
        ApiError { status: StatusCode::UNPROCESSABLE_ENTITY, field, message }
    }
    /// 503: the server cannot take it now.
    pub fn unavailable(message: String) -> ApiError {
        ApiError { status: StatusCode::SERVICE_UNAVAILABLE, field: None, message }
    }
    /// 500: the server failed.
    pub(super) fn internal(message: String) -> ApiError {
        ApiError { status: StatusCode::INTERNAL_SERVER_ERROR, field: None, message }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        (self.status, Json(json!({ "error": self.message, "field": self.field }))).into_response()
    }
}
